/// \file renderer.cpp
/// \brief Block-based image renderer, single-threaded or on oneTBB (implementation).
#include <nori/block.h>
#include <nori/progress.h>
#include <nori/renderer.h>
#include <nori/rfilter.h>
#include <nori/scene.h>
#include <chrono>
#include <map>
#include <mutex>
#include <tbb/parallel_for.h>

namespace nori {

namespace {

/// Renders one block: every pixel, every sample, splatted with the camera's filter.
BlockTally renderBlock(const Scene &scene, Sampler &sampler, ImageBlock &block) {
    const Camera &camera = scene.camera();
    const Integrator &integrator = scene.integrator();
    const Point2i offset = block.offset();
    const Vector2i size = block.size();
    const int spp = sampler.sampleCount();
    const Scene::RayCounts before = Scene::threadRayCounts();
    for (int y = 0; y < size.y(); ++y)
        for (int x = 0; x < size.x(); ++x)
            for (int s = 0; s < spp; ++s) {
                Point2f pixel = Point2f(float(offset.x() + x), float(offset.y() + y)) + sampler.next2D();
                Ray3f ray;
                Color3f weight = camera.sampleRay(ray, pixel, sampler.next2D());
                block.put(pixel, weight * integrator.Li(scene, sampler, ray));
            }
    const Scene::RayCounts after = Scene::threadRayCounts();
    BlockTally tally;
    tally.cameraRays = uint64_t(size.x()) * uint64_t(size.y()) * uint64_t(spp);
    tally.closestHitRays = after.closestHit - before.closestHit;
    tally.shadowRays = after.shadow - before.shadow;
    tally.droppedSamples = block.droppedSamples();
    return tally;
}

/// Collects finished blocks and adds them to the image strictly in block-index order:
/// float sums then do not depend on which thread finished first.
class OrderedMerger {
public:
    OrderedMerger(ImageBlock &image) : m_image(image) {}

    void add(int index, ImageBlock &&block) {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_pending.emplace(index, std::move(block));
        for (auto it = m_pending.find(m_next); it != m_pending.end(); it = m_pending.find(++m_next)) {
            m_image.put(it->second);
            m_pending.erase(it);
        }
    }

    /// After a cancelled render: add what finished beyond the first gap, still in order.
    void flush() {
        std::lock_guard<std::mutex> lock(m_mutex);
        for (auto &entry : m_pending) m_image.put(entry.second);
        m_pending.clear();
    }

private:
    ImageBlock &m_image;
    std::mutex m_mutex;
    std::map<int, ImageBlock> m_pending;
    int m_next = 0;
};

} // namespace

RenderResult BlockRenderer::render(const RenderSettings &settings) const {
    auto start = std::chrono::steady_clock::now();
    const Camera &camera = m_scene.camera();
    const Vector2i outputSize = camera.outputSize();
    const ReconstructionFilter *filter = camera.reconstructionFilter();
    BlockGenerator generator(outputSize, 32);
    ImageBlock image(outputSize, filter);
    image.clear();
    OrderedMerger merger(image);
    ProgressReporter progress("Rendering", generator.blockCount(), settings.progress);

    std::atomic<int> rendered{0};
    std::atomic<uint64_t> cameraRays{0}, closestHitRays{0}, shadowRays{0}, dropped{0};
    auto cancelled = [&] { return settings.cancel && settings.cancel->load(); };
    // A finished block joins this process's image (from this process or, through the exchange,
    // from another one).
    auto merge = [&](int index, ImageBlock &&block, const BlockTally &tally) {
        cameraRays += tally.cameraRays;
        closestHitRays += tally.closestHitRays;
        shadowRays += tally.shadowRays;
        dropped += tally.droppedSamples;
        merger.add(index, std::move(block));
        ++rendered;
        progress.advance();
    };
    BlockExchange *exchange = settings.exchange;
    auto work = [&](int index) {
        if (cancelled()) return;
        ImageBlock block(Vector2i(32, 32), filter);
        generator.prepare(index, block);
        std::unique_ptr<Sampler> sampler = m_scene.sampler().clone();
        sampler->prepare(uint64_t(index));
        BlockTally tally = renderBlock(m_scene, *sampler, block);
        if (exchange) exchange->deliver(index, std::move(block), tally);
        else merge(index, std::move(block), tally);
    };

    if (exchange) {
        // Blocks come from the exchange, one claim at a time, until it has none left for us.
        exchange->start(generator, filter, merge);
        auto claimLoop = [&] {
            for (int index; !cancelled() && exchange->claim(index);) work(index);
        };
        if (settings.threads == 1) claimLoop();
        else tbb::parallel_for(0, std::max(1, settings.threads), [&](int) { claimLoop(); }, tbb::simple_partitioner());
        exchange->finish();
    } else if (settings.threads == 1) {
        for (int i = 0; i < generator.blockCount(); ++i) work(i);
    } else {
        // One task per block; tbb::global_control (set by the caller) bounds the threads.
        tbb::parallel_for(tbb::blocked_range<int>(0, generator.blockCount(), 1),
                          [&](const tbb::blocked_range<int> &range) {
                              for (int i = range.begin(); i != range.end(); ++i) work(i);
                          },
                          tbb::simple_partitioner());
    }
    merger.flush();
    progress.finish();

    RenderResult result;
    result.image = image.toBitmap();
    result.blockCount = generator.blockCount();
    result.blocksRendered = rendered.load();
    result.complete = result.blocksRendered == result.blockCount;
    result.cameraRays = cameraRays.load();
    result.closestHitRays = closestHitRays.load();
    result.shadowRays = shadowRays.load();
    result.rays = result.closestHitRays + result.shadowRays;
    // Each merged block's count also went into the image (ImageBlock::put of a block adds it):
    // count it once, from the tallies, which blocks from other ranks carry too.
    result.droppedSamples = dropped.load();
    if (exchange) result.ranks = exchange->shares();
    result.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

} // namespace nori
