#!/bin/sh
# Build the libFuzzer targets with clang and run each for a bounded time.
#   tests/fuzz/run_fuzz.sh [SECONDS]   (default 60 seconds per target)
# Crashes land in build-fuzz/artifacts/; turn each one into a case in tests/data/bad/.
set -eu
SECONDS_PER_TARGET=${1:-60}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$ROOT/build-fuzz
JOBS=$(nproc 2>/dev/null || echo 2)

CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNORI_FUZZ=ON \
    -DNORI_BUILD_TESTS=OFF -DNORI_BUILD_BENCH=OFF -DNORI_ARCH= >/dev/null
cmake --build "$BUILD" -j"$JOBS" --target fuzz_scene fuzz_obj

# Seed corpora: the project's own scenes and meshes, good and bad.
mkdir -p "$BUILD/corpus/scene" "$BUILD/corpus/obj" "$BUILD/artifacts"
for f in "$ROOT"/tests/data/bad/*.xml "$ROOT"/scenes/*.xml; do [ -f "$f" ] && cp "$f" "$BUILD/corpus/scene/"; done
for f in "$ROOT"/tests/data/bad/*.obj; do [ -f "$f" ] && cp "$f" "$BUILD/corpus/obj/"; done

status=0
for target in scene obj; do
    case $target in scene) maxlen=4096 ;; obj) maxlen=65536 ;; esac
    echo "== fuzz_$target for $SECONDS_PER_TARGET s"
    if ! "$BUILD/tests/fuzz/fuzz_$target" "$BUILD/corpus/$target" -max_total_time="$SECONDS_PER_TARGET" \
        -max_len=$maxlen -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
        -artifact_prefix="$BUILD/artifacts/$target-" 2>"$BUILD/fuzz_$target.log"; then
        status=1
    fi
    grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|Done|INFO: Running with)|ERROR|SUMMARY" \
        "$BUILD/fuzz_$target.log" || true
done
if ls "$BUILD"/artifacts/* >/dev/null 2>&1; then
    echo "Artifacts (add each as a case in tests/data/bad/ with a MANIFEST.tsv row):"
    ls -l "$BUILD"/artifacts/
    status=1
fi
exit $status
