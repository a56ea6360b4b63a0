/// \file bench_runner.cpp
/// \brief Runs every contender on one input, interleaved with Embree, and collects the results (implementation).
#include "bench_runner.h"
#include "embree_oracle.h"
#include "oracle_judge.h"
#include "ray_sets.h"
#include "ray_workload.h"
#include "accel/lanes.h"
#include <nori/object.h>
#include <tbb/info.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace nori::bench {

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void finish(SetTiming &s) {
    s.ms = median(s.samples);
    s.mraysPerS = s.ms > 0.0 ? double(s.rays) / (s.ms * 1e3) : 0.0;
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

BenchRunner::BenchRunner(const BenchOptions &options, const OctreeCatalog &catalog)
    : m_options(options), m_catalog(catalog), m_timer(options.threads, options.cpuTime),
      m_threads(options.threads > 0 ? options.threads : tbb::info::default_concurrency()) {
    if (!options.dumpDisputed.empty()) {
        m_dump.reset(std::fopen(options.dumpDisputed.c_str(), "w"), [](std::FILE *f) {
            if (f) std::fclose(f);
        });
        if (!m_dump) throw std::runtime_error(options.dumpDisputed + ": cannot open for writing");
    }
    if (!options.dumpAnswers.empty()) {
        m_answers.reset(std::fopen(options.dumpAnswers.c_str(), "wb"), [](std::FILE *f) {
            if (f) std::fclose(f);
        });
        if (!m_answers) throw std::runtime_error(options.dumpAnswers + ": cannot open for writing");
    }
}

template <typename Tracer>
std::array<SetTiming, 3> BenchRunner::interleaved(const Tracer &tracer, const EmbreeOracle &embree,
                                                  const RayWorkload &work,
                                                  std::array<std::vector<double>, 3> *embreeSamples) const {
    std::array<SetTiming, 3> out;
    std::vector<float> answers, embreeAnswers;
    for (int s = 0; s < RayWorkload::Count; ++s) {
        const RaySet &set = work.set(s);
        SetTiming &t = out[size_t(s)];
        t.name = set.name;
        t.rays = set.size();
        std::vector<double> embreeRuns;
        // Embree, contender, Embree, contender ...: slow drift of the machine hits both alike.
        for (int r = 0; r < m_options.repeats; ++r) {
            embreeRuns.push_back(m_timer.trace(embree, set, embreeAnswers));
            t.samples.push_back(m_timer.trace(tracer, set, answers));
        }
        finish(t);
        t.embreeMs = median(embreeRuns);
        t.ratioVsEmbree = t.ms > 0.0 ? t.embreeMs / t.ms : 0.0;
        t.hasAccuracy = true;
        t.accuracy = Accuracy::compare(answers, set.reference, set.rays);
        referee(tracer, embree, set, embreeAnswers, t.accuracy);
        if (m_answers && !m_dumpWho.empty()) {
            // One record of nine floats per ray: o, d, mint, maxt, the answer (as RaySet::reference).
            for (size_t r = 0; r < set.rays.size(); ++r) {
                const Ray3f &ray = set.rays[r];
                const float rec[9] = {ray.o.x(), ray.o.y(), ray.o.z(), ray.d.x(), ray.d.y(), ray.d.z(), ray.mint, ray.maxt, answers[r]};
                std::fwrite(rec, sizeof(float), 9, m_answers.get());
            }
        }
        if (embreeSamples) {
            auto &dst = (*embreeSamples)[size_t(s)];
            dst.insert(dst.end(), embreeRuns.begin(), embreeRuns.end());
        }
    }
    return out;
}

template <typename Tracer>
void BenchRunner::referee(const Tracer &tracer, const EmbreeOracle &peer, const RaySet &set,
                          const std::vector<float> &peerAnswers, Accuracy &accuracy) const {
    if (!m_judge || !m_robust) return;
    std::vector<uint32_t> rays = accuracy.mismatchRays;
    const Accuracy peerAccuracy = Accuracy::compare(peerAnswers, set.reference, set.rays);
    rays.insert(rays.end(), peerAccuracy.mismatchRays.begin(), peerAccuracy.mismatchRays.end());
    std::sort(rays.begin(), rays.end());
    rays.erase(std::unique(rays.begin(), rays.end()), rays.end());
    accuracy.refereed = true;
    accuracy.disputed = rays.size();
    for (uint32_t i : rays) {
        // Closest hits behind the answers (for shadow rays too: what occluded them).
        const Ray3f &ray = set.rays[i];
        Hit hits[3];
        bool hit[3] = {tracer.intersect(ray, hits[0]), peer.intersect(ray, hits[1]), m_robust->intersect(ray, hits[2])};
        std::vector<uint32_t> candidates;
        for (int k = 0; k < 3; ++k)
            if (hit[k]) candidates.push_back(hits[k].prim);
        int verdict[3];
        for (int k = 0; k < 3; ++k) verdict[k] = m_judge->referee(ray, hit[k], hits[k], candidates);
        accuracy.exactWrong += verdict[0] < 0;
        accuracy.peerWrong += verdict[1] < 0;
        accuracy.referenceWrong += verdict[2] < 0;
        if (m_dump && !m_dumpWho.empty()) dumpRay(set, i, hit, hits, verdict);
    }
}

void BenchRunner::dumpRay(const RaySet &set, uint32_t index, const bool hit[3], const Hit hits[3],
                          const int verdict[3]) const {
    // Text, one record per ray; floats as %a so that a test can replay the ray bit for bit.
    std::FILE *f = m_dump.get();
    const Ray3f &r = set.rays[index];
    std::fprintf(f, "ray %s %u o %a %a %a d %a %a %a mint %a maxt %a\n", set.name.c_str(), index,
                 r.o.x(), r.o.y(), r.o.z(), r.d.x(), r.d.y(), r.d.z(), r.mint, r.maxt);
    const char *names[3] = {"octree", "default", "robust"};
    for (int k = 0; k < 3; ++k) {
        const char *v = verdict[k] > 0 ? "right" : verdict[k] < 0 ? "WRONG" : "undecidable";
        if (hit[k])
            std::fprintf(f, "  %s hit t %a (%.9g) prim %u u %a v %a %s\n", names[k], hits[k].t, hits[k].t, hits[k].prim,
                         hits[k].u, hits[k].v, v);
        else
            std::fprintf(f, "  %s miss %s\n", names[k], v);
    }
    std::vector<uint32_t> prims;
    for (int k = 0; k < 3; ++k)
        if (hit[k] && std::find(prims.begin(), prims.end(), hits[k].prim) == prims.end()) prims.push_back(hits[k].prim);
    for (uint32_t prim : prims) {
        uint32_t local = prim;
        for (const Mesh *m : m_dumpMeshes) {
            if (local >= m->triangleCount()) {
                local -= m->triangleCount();
                continue;
            }
            std::fprintf(f, "  tri %u", prim);
            for (int c = 0; c < 3; ++c) {
                const Point3f p = m->vertex(local, c);
                std::fprintf(f, " %a %a %a", p.x(), p.y(), p.z());
            }
            std::fprintf(f, "\n");
            break;
        }
    }
}

void BenchRunner::progress(const std::string &what, const RunResult &run) const {
    std::string line = fmt::format("[nori-bench]   {:<34} build {:>9.1f} ms", what, run.buildMs);
    for (const SetTiming &s : run.sets)
        line += fmt::format(" | {} {:.3f} Mr/s {:.2f}x {} mism ({} wrong)", s.name, s.mraysPerS, s.ratioVsEmbree,
                            s.accuracy.mismatches, s.accuracy.exactWrong);
    std::fprintf(stderr, "%s\n", line.c_str());
}

RunResult BenchRunner::runAccel(const std::string &accelName, Accel &accel, const OctreeConfig *config,
                                const BenchInput &input, const EmbreeOracle &embree, const RayWorkload &work,
                                std::array<std::vector<double>, 3> *embreeSamples) const {
    RunResult run;
    run.accel = accelName;
    if (config) {
        run.hasConfig = true;
        run.config = *config;
    }
    for (const Mesh *mesh : input.meshPointers()) accel.addMesh(mesh);
    accel.build();
    run.buildMs = m_options.cpuTime ? accel.buildCpuMilliseconds() : accel.buildMilliseconds();
    run.stats = accel.statistics();
    run.sets = interleaved(accel, embree, work, embreeSamples);
    return run;
}

namespace {
/// The CPU's model name from /proc/cpuinfo ("unknown" where there is none).
std::string cpuName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            const size_t colon = line.find(':');
            if (colon != std::string::npos && colon + 2 <= line.size()) return line.substr(colon + 2);
        }
    return "unknown";
}
} // namespace

MeshResult BenchRunner::run(const BenchInput &input) const {
    MeshResult result;
    result.mesh = input.name;
    result.triangles = input.triangleCount();
    result.threads = m_threads;
    result.loadMs = input.loadMs;
    result.repeats = m_options.repeats;
    result.clock = m_options.cpuTime ? "cpu" : "wall";
    result.cpu = cpuName();
    result.cpuAvx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
    result.octreeLanes = lanes::kMaxLanes;
    result.notes = m_catalog.skipped();
    std::vector<const Mesh *> meshes = input.meshPointers();
    MeshTable table(meshes);
    OracleJudge judge(meshes);

    std::fprintf(stderr, "[nori-bench] %s: %llu triangles, loaded in %.1f ms, %d thread(s)\n", input.name.c_str(),
                 (unsigned long long)result.triangles, input.loadMs, m_threads);

    // Embree: the robust scene is the accuracy reference, the default one the speed peer.
    // Builds are repeated and the median kept (they are cheap next to the ray sets).
    int embreeThreads = m_options.threads;  // 0: Embree's default (all cores)
    std::vector<double> fastBuilds, robustBuilds;
    std::unique_ptr<EmbreeOracle> fast, robust;
    for (int r = 0; r < m_options.repeats; ++r) {
        fast.reset();
        robust.reset();
        fast = std::make_unique<EmbreeOracle>(meshes, EmbreeOracle::Options{false, embreeThreads});
        fastBuilds.push_back(m_options.cpuTime ? fast->buildCpuMilliseconds() : fast->buildMilliseconds());
        robust = std::make_unique<EmbreeOracle>(meshes, EmbreeOracle::Options{true, embreeThreads});
        robustBuilds.push_back(m_options.cpuTime ? robust->buildCpuMilliseconds() : robust->buildMilliseconds());
    }
    result.embree.buildMs = median(fastBuilds);
    result.embree.bytes = fast->bytes();
    result.embreeRobust.buildMs = median(robustBuilds);
    result.embreeRobust.bytes = robust->bytes();
    m_judge = &judge;
    m_robust = robust.get();
    m_dumpMeshes = meshes;
    if (m_dump) std::fprintf(m_dump.get(), "input %s\n", input.name.c_str());
    std::fprintf(stderr, "[nori-bench]   embree build %.1f ms (%lld bytes), robust %.1f ms (%lld bytes)\n",
                 result.embree.buildMs, result.embree.bytes, result.embreeRobust.buildMs, result.embreeRobust.bytes);

    // Ray sets (not timed as part of any contender).
    auto genStart = std::chrono::steady_clock::now();
    std::unique_ptr<Camera> framing;
    const Camera *camera = input.camera();
    if (camera) {
        result.camera = "scene";
    } else {
        framing = framingCamera(table.bbox(), m_options.width, m_options.height);
        camera = framing.get();
        result.camera = "framing";
    }
    result.width = camera->outputSize().x();
    result.height = camera->outputSize().y();
    result.spp = m_options.spp;
    RayWorkload work(*camera, m_options.spp, *robust, table);
    result.rayGenerationMs = msSince(genStart);
    std::fprintf(stderr, "[nori-bench]   rays: primary %zu, diffuse %zu, shadow %zu (generated in %.0f ms)\n",
                 work.set(0).size(), work.set(1).size(), work.set(2).size(), result.rayGenerationMs);

    // Warm-up (untimed): thread pools, caches and page faults of the first pass.
    {
        std::vector<float> scratch;
        for (const RaySet &set : work.sets()) m_timer.trace(*fast, set, scratch);
    }
    std::array<std::vector<double>, 3> embreeSamples;

    // Embree robust against Embree default, interleaved like any contender.
    {
        std::array<SetTiming, 3> robustSets = interleaved(*robust, *fast, work, &embreeSamples);
        result.embreeRobust.sets = robustSets;
    }

    // The octree configurations.
    const auto &configs = m_catalog.configs();
    for (size_t c = 0; c < configs.size(); ++c) {
        // Build time: the median of --repeats builds, as for Embree (one build moves by 2x when
        // the machine is shared); the extra builds are timed only.
        std::vector<double> builds;
        for (int r = 1; r < m_options.repeats; ++r) {
            std::unique_ptr<Accel> extra = OctreeCatalog::create(configs[c]);
            for (const Mesh *mesh : input.meshPointers()) extra->addMesh(mesh);
            extra->build();
            builds.push_back(m_options.cpuTime ? extra->buildCpuMilliseconds() : extra->buildMilliseconds());
        }
        std::unique_ptr<Accel> accel = OctreeCatalog::create(configs[c]);
        m_dumpWho = configs[c].label();
        if (m_dump) std::fprintf(m_dump.get(), "run %s\n", m_dumpWho.c_str());
        RunResult run = runAccel("octree", *accel, &configs[c], input, *fast, work, &embreeSamples);
        m_dumpWho.clear();
        builds.push_back(run.buildMs);
        run.buildMs = median(builds);
        result.runs.push_back(std::move(run));
        progress(fmt::format("[{}/{}] {}", c + 1, configs.size(), configs[c].label()), result.runs.back());
    }

    // Brute force on a strided subset of each ray set, against Embree on the same subset.
    if (m_options.noBrute) {
        std::fprintf(stderr, "[nori-bench]   brute force skipped (--no-brute)\n");
    } else if (result.triangles > m_options.bruteMaxTriangles) {
        std::fprintf(stderr, "[nori-bench]   brute force skipped (%llu triangles > %zu)\n",
                     (unsigned long long)result.triangles, m_options.bruteMaxTriangles);
    } else {
        RayWorkload subset = work.subset(m_options.bruteRays);
        std::unique_ptr<NoriObject> object =
            NoriObjectFactory::createInstance(NoriObject::EAccel, "brute", PropertyList());
        Accel &brute = static_cast<Accel &>(*object);
        RunResult run = runAccel("brute", brute, nullptr, input, *fast, subset, nullptr);
        result.runs.push_back(std::move(run));
        progress(fmt::format("brute ({} rays/set)", subset.set(0).size()), result.runs.back());
    }

    // Embree's own numbers: the median of all its interleaved runs; its accuracy vs robust.
    std::vector<float> answers;
    for (int s = 0; s < RayWorkload::Count; ++s) {
        SetTiming &t = result.embree.sets[size_t(s)];
        t.name = work.set(s).name;
        t.rays = work.set(s).size();
        t.samples = embreeSamples[size_t(s)];
        finish(t);
        t.embreeMs = t.ms;
        t.ratioVsEmbree = 1.0;
        m_timer.trace(*fast, work.set(s), answers);
        t.hasAccuracy = true;
        t.accuracy = Accuracy::compare(answers, work.set(s).reference, work.set(s).rays);
        referee(*fast, *fast, work.set(s), answers, t.accuracy);
    }
    m_judge = nullptr;
    m_robust = nullptr;
    const auto &e = result.embree.sets;
    std::fprintf(stderr, "[nori-bench]   embree: primary %.3f, diffuse %.3f, shadow %.3f Mrays/s\n",
                 e[0].mraysPerS, e[1].mraysPerS, e[2].mraysPerS);
    return result;
}

} // namespace nori::bench
