/// \file test_image.cpp
/// \brief Tests of the image pipeline: reconstruction filters, ImageBlock, BlockGenerator and Bitmap I/O.
#include <gtest/gtest.h>
#include <nori/bitmap.h>
#include <nori/block.h>
#include <nori/rfilter.h>
#include <stb_image.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sys/resource.h>
#include <thread>
#include <unistd.h>

using namespace nori;
namespace fs = std::filesystem;

namespace {

std::unique_ptr<ReconstructionFilter> makeFilter(const std::string &type, const PropertyList &props = {}) {
    std::unique_ptr<NoriObject> object =
        NoriObjectFactory::createInstance(NoriObject::EReconstructionFilter, type, props);
    auto *filter = dynamic_cast<ReconstructionFilter *>(object.get());
    if (!filter) throw std::runtime_error("not a reconstruction filter: " + type);
    object.release();
    return std::unique_ptr<ReconstructionFilter>(filter);
}

PropertyList floatProps(const std::string &name, float value) {
    PropertyList props;
    props.setLocation("scene.xml:3");
    props.setFloat(name, value, "scene.xml:7");
    return props;
}

/// Sum of the weights of every pixel (border included) of \p block.
float totalWeight(const ImageBlock &block) {
    float sum = 0.0f;
    const int b = block.borderSize();
    for (int y = -b; y < block.size().y() + b; ++y)
        for (int x = -b; x < block.size().x() + b; ++x) sum += block.pixel(x, y)[3];
    return sum;
}

std::string readFile(const fs::path &path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> listDirectory(const fs::path &dir) {
    std::vector<std::string> names;
    for (const auto &entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// A fresh, empty folder per test (tests may run in parallel processes).
class ImageFiles : public ::testing::Test {
protected:
    void SetUp() override {
        const auto *info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_dir = fs::temp_directory_path() /
                fmt::format("nori-image-{}-{}-{}", long(::getpid()), info->test_suite_name(), info->name());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(m_dir, ec);
    }
    fs::path m_dir;
};

/// Temporarily limit the size of files this process may write (RLIMIT_FSIZE), so that writes fail
/// with EFBIG part-way. Unlike permission tricks this also works when the tests run as root.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &m_saved);
        m_savedHandler = std::signal(SIGXFSZ, SIG_IGN); // otherwise the kernel kills the process
        rlimit limit = m_saved;
        limit.rlim_cur = bytes;
        m_ok = setrlimit(RLIMIT_FSIZE, &limit) == 0;
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &m_saved);
        std::signal(SIGXFSZ, m_savedHandler);
    }
    bool ok() const { return m_ok; }

private:
    rlimit m_saved{};
    void (*m_savedHandler)(int) = nullptr;
    bool m_ok = false;
};

/// A bitmap of pseudo-random colours that compresses badly (so that its files are large).
Bitmap noiseBitmap(int width, int height, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Bitmap bitmap(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) bitmap(y, x) = Color3f(u(rng), u(rng), u(rng));
    return bitmap;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Reconstruction filters
// ---------------------------------------------------------------------------------------------

TEST(ReconstructionFilter, AllTypesAreRegistered) {
    for (const char *name : {"gaussian", "box", "tent", "mitchell"}) {
        EXPECT_TRUE(NoriObjectFactory::isRegistered(NoriObject::EReconstructionFilter, name)) << name;
        EXPECT_EQ(makeFilter(name)->getClassType(), NoriObject::EReconstructionFilter);
    }
}

TEST(ReconstructionFilter, BoxIsConstantInsideAndZeroOutside) {
    auto box = makeFilter("box");
    EXPECT_EQ(box->radius(), 0.5f);
    for (float x : {0.0f, 0.1f, -0.25f, 0.49f, -0.5f, 0.5f}) EXPECT_EQ(box->eval(x), 1.0f) << x;
    for (float x : {0.501f, -0.6f, 1.0f, -3.0f}) EXPECT_EQ(box->eval(x), 0.0f) << x;
}

TEST(ReconstructionFilter, TentIsLinear) {
    auto tent = makeFilter("tent");
    EXPECT_EQ(tent->radius(), 1.0f);
    EXPECT_FLOAT_EQ(tent->eval(0.0f), 1.0f);
    EXPECT_FLOAT_EQ(tent->eval(0.25f), 0.75f);
    EXPECT_FLOAT_EQ(tent->eval(-0.5f), 0.5f);
    EXPECT_EQ(tent->eval(1.0f), 0.0f);
    EXPECT_EQ(tent->eval(1.5f), 0.0f);
    // Second differences of a linear function vanish.
    for (float x = 0.05f; x < 0.9f; x += 0.1f)
        EXPECT_NEAR(tent->eval(x - 0.05f) - 2.0f * tent->eval(x) + tent->eval(x + 0.05f), 0.0f, 1e-6f) << x;

    auto wide = makeFilter("tent", floatProps("radius", 3.0f));
    EXPECT_EQ(wide->radius(), 3.0f);
    EXPECT_FLOAT_EQ(wide->eval(1.5f), 0.5f);
}

TEST(ReconstructionFilter, GaussianReachesZeroAtRadius) {
    auto gauss = makeFilter("gaussian");
    EXPECT_EQ(gauss->radius(), 2.0f);
    // Defaults: stddev 0.5, so exp(-x^2 / 0.5) - exp(-8).
    EXPECT_NEAR(gauss->eval(0.0f), 1.0f - std::exp(-8.0f), 1e-6f);
    EXPECT_NEAR(gauss->eval(0.5f), std::exp(-0.5f) - std::exp(-8.0f), 1e-6f);
    EXPECT_NEAR(gauss->eval(2.0f), 0.0f, 1e-7f);
    EXPECT_NEAR(gauss->eval(1.999f), 0.0f, 1e-5f);
    EXPECT_EQ(gauss->eval(2.5f), 0.0f);
    float previous = gauss->eval(0.0f);
    for (float x = 0.1f; x <= 2.0f; x += 0.1f) {
        EXPECT_LT(gauss->eval(x), previous) << x;
        EXPECT_EQ(gauss->eval(x), gauss->eval(-x)) << x;
        previous = gauss->eval(x);
    }

    PropertyList props;
    props.setFloat("radius", 1.0f);
    props.setFloat("stddev", 2.0f);
    auto broad = makeFilter("gaussian", props);
    EXPECT_NEAR(broad->eval(1.0f), 0.0f, 1e-7f);
    EXPECT_NEAR(broad->eval(0.0f), 1.0f - std::exp(-1.0f / 8.0f), 1e-6f);
}

TEST(ReconstructionFilter, MitchellShape) {
    auto mitchell = makeFilter("mitchell");
    EXPECT_EQ(mitchell->radius(), 2.0f);
    // Integral over the support by the midpoint rule: the kernel is normalised at radius 2.
    const int n = 20000;
    double integral = 0.0;
    for (int i = 0; i < n; ++i) integral += mitchell->eval(-2.0f + 4.0f * (float(i) + 0.5f) / float(n));
    integral *= 4.0 / n;
    EXPECT_NEAR(integral, 1.0, 1e-4);
    // k(0) = (6 - 2B) / 6 with B = 1/3.
    EXPECT_NEAR(mitchell->eval(0.0f), (6.0f - 2.0f / 3.0f) / 6.0f, 1e-6f);
    // Continuous at the knot |x| = 1, negative lobe beyond it, zero at and beyond the radius.
    EXPECT_NEAR(mitchell->eval(0.9999f), mitchell->eval(1.0001f), 1e-3f);
    EXPECT_LT(mitchell->eval(1.5f), 0.0f);
    EXPECT_NEAR(mitchell->eval(2.0f), 0.0f, 1e-7f);
    EXPECT_EQ(mitchell->eval(2.5f), 0.0f);
    EXPECT_EQ(mitchell->eval(-0.7f), mitchell->eval(0.7f));

    // B = 1, C = 0 is the cubic B-spline: non-negative everywhere, k(0) = 4/6.
    PropertyList props;
    props.setFloat("B", 1.0f);
    props.setFloat("C", 0.0f);
    auto spline = makeFilter("mitchell", props);
    EXPECT_NEAR(spline->eval(0.0f), 4.0f / 6.0f, 1e-6f);
    for (float x = 0.0f; x <= 2.0f; x += 0.05f) EXPECT_GE(spline->eval(x), 0.0f) << x;

    // A stretched kernel keeps its shape: k_r(x) = k_2(2x / r).
    auto stretched = makeFilter("mitchell", floatProps("radius", 4.0f));
    EXPECT_NEAR(stretched->eval(3.0f), mitchell->eval(1.5f), 1e-6f);
}

TEST(ReconstructionFilter, RejectsBadParameters) {
    struct Case {
        const char *type, *property;
        float value;
    };
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const Case cases[] = {
        {"gaussian", "radius", 0.0f},  {"gaussian", "radius", -1.0f}, {"gaussian", "radius", nan},
        {"gaussian", "radius", Infinity}, {"gaussian", "stddev", 0.0f}, {"gaussian", "stddev", -0.5f},
        {"tent", "radius", 0.0f},      {"tent", "radius", nan},       {"mitchell", "radius", -2.0f},
        {"mitchell", "B", nan},        {"mitchell", "C", Infinity},
    };
    for (const Case &c : cases) {
        try {
            makeFilter(c.type, floatProps(c.property, c.value));
            ADD_FAILURE() << c.type << " accepted " << c.property << " = " << c.value;
        } catch (const NoriException &e) {
            // The message points at the offending property's declaration.
            EXPECT_EQ(std::string(e.what()).rfind("scene.xml:7: ", 0), 0u) << e.what();
            EXPECT_NE(std::string(e.what()).find(c.property), std::string::npos) << e.what();
        }
    }
}

// ---------------------------------------------------------------------------------------------
// ImageBlock
// ---------------------------------------------------------------------------------------------

TEST(ImageBlock, BorderSizeFollowsRadius) {
    EXPECT_EQ(ImageBlock(Vector2i(4, 4), makeFilter("box").get()).borderSize(), 0);
    EXPECT_EQ(ImageBlock(Vector2i(4, 4), nullptr).borderSize(), 0);
    EXPECT_EQ(ImageBlock(Vector2i(4, 4), makeFilter("tent").get()).borderSize(), 1);
    EXPECT_EQ(ImageBlock(Vector2i(4, 4), makeFilter("tent", floatProps("radius", 1.5f)).get()).borderSize(), 1);
    EXPECT_EQ(ImageBlock(Vector2i(4, 4), makeFilter("tent", floatProps("radius", 1.6f)).get()).borderSize(), 2);
    EXPECT_EQ(ImageBlock(Vector2i(4, 4), makeFilter("gaussian").get()).borderSize(), 2);
}

TEST(ImageBlock, BoxSampleAtPixelCentreLandsInOnePixel) {
    auto box = makeFilter("box");
    ImageBlock block(Vector2i(8, 6), box.get());
    block.setOffset(Point2i(10, 20));
    EXPECT_TRUE(block.put(Point2f(13.5f, 22.5f), Color3f(1.0f, 2.0f, 3.0f)));
    // A sample on a pixel corner also goes to exactly one pixel (half-open footprint).
    EXPECT_TRUE(block.put(Point2f(15.0f, 24.0f), Color3f(4.0f, 5.0f, 6.0f)));
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            Eigen::Array4f p = block.pixel(x, y);
            if (x == 3 && y == 2)
                EXPECT_TRUE((p == Eigen::Array4f(1, 2, 3, 1)).all()) << p.transpose();
            else if (x == 5 && y == 4)
                EXPECT_TRUE((p == Eigen::Array4f(4, 5, 6, 1)).all()) << p.transpose();
            else
                EXPECT_TRUE((p == 0.0f).all()) << x << "," << y << ": " << p.transpose();
        }
    Bitmap bitmap = block.toBitmap();
    ASSERT_EQ(bitmap.width(), 8);
    ASSERT_EQ(bitmap.height(), 6);
    EXPECT_TRUE((bitmap(2, 3) == Color3f(1, 2, 3)).all());
    EXPECT_TRUE((bitmap(0, 0) == Color3f(0, 0, 0)).all());
}

TEST(ImageBlock, FilterTableMatchesFilter) {
    for (const char *type : {"gaussian", "tent", "mitchell", "box"}) {
        auto filter = makeFilter(type);
        ImageBlock block(Vector2i(1, 1), filter.get());
        for (float x = -filter->radius(); x <= filter->radius(); x += 0.01f)
            EXPECT_NEAR(block.filterWeight(x), filter->eval(x), 3e-3f) << type << " at " << x;
        EXPECT_EQ(block.filterWeight(filter->radius() * 1.01f), 0.0f) << type;
        EXPECT_EQ(block.filterWeight(std::numeric_limits<float>::quiet_NaN()), 0.0f) << type;
    }
}

TEST(ImageBlock, GaussianWeightsSumCorrectly) {
    auto gauss = makeFilter("gaussian");
    ImageBlock block(Vector2i(12, 12), gauss.get());
    const Point2f pos(5.3f, 4.7f);
    const Color3f value(0.25f, 2.0f, 8.0f);
    ASSERT_TRUE(block.put(pos, value));

    // Reference: the exact separable weights of every pixel whose centre is within the radius.
    double expected = 0.0;
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x)
            expected += double(gauss->eval(pos.x() - (x + 0.5f))) * double(gauss->eval(pos.y() - (y + 0.5f)));
    EXPECT_NEAR(totalWeight(block), expected, 1e-3 * expected);
    EXPECT_GT(expected, 1.0); // the footprint covers several pixels

    // Every pixel reached stores value * weight, so the reconstruction is the sample's value.
    Bitmap bitmap = block.toBitmap();
    int covered = 0;
    for (int y = 0; y < 12; ++y)
        for (int x = 0; x < 12; ++x) {
            float w = block.pixel(x, y)[3];
            if (w > 0.0f) {
                ++covered;
                EXPECT_NEAR(bitmap(y, x)[1], 2.0f, 1e-5f);
                EXPECT_NEAR(bitmap(y, x)[2], 8.0f, 4e-5f);
            } else {
                EXPECT_TRUE((bitmap(y, x) == 0.0f).all());
            }
        }
    EXPECT_EQ(covered, 16); // 4 x 4 pixel centres within distance 2 of (5.3, 4.7) on each axis
}

TEST(ImageBlock, SampleOutsideBlockIsClippedNotDropped) {
    auto gauss = makeFilter("gaussian");
    ImageBlock block(Vector2i(4, 4), gauss.get());
    block.setOffset(Point2i(8, 8));
    EXPECT_TRUE(block.put(Point2f(100.0f, 100.0f), Color3f(1, 1, 1)));
    EXPECT_TRUE(block.put(Point2f(-1e30f, 3e30f), Color3f(1, 1, 1)));
    EXPECT_EQ(totalWeight(block), 0.0f);
    EXPECT_EQ(block.droppedSamples(), 0u);
    // A sample just outside the inner region still reaches the border and the inner edge.
    EXPECT_TRUE(block.put(Point2f(7.9f, 9.5f), Color3f(1, 1, 1)));
    EXPECT_GT(block.pixel(-1, 1)[3], 0.0f);
    EXPECT_GT(block.pixel(0, 1)[3], 0.0f);
}

TEST(ImageBlock, NonFiniteSamplesAreDropped) {
    auto gauss = makeFilter("gaussian");
    ImageBlock block(Vector2i(6, 6), gauss.get());
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(block.put(Point2f(3.0f, 3.0f), Color3f(nan, 0.0f, 0.0f)));
    EXPECT_FALSE(block.put(Point2f(3.0f, 3.0f), Color3f(0.0f, Infinity, 0.0f)));
    EXPECT_FALSE(block.put(Point2f(nan, 3.0f), Color3f(1.0f, 1.0f, 1.0f)));
    EXPECT_FALSE(block.put(Point2f(3.0f, -Infinity), Color3f(1.0f, 1.0f, 1.0f)));
    EXPECT_EQ(block.droppedSamples(), 4u);
    EXPECT_EQ(totalWeight(block), 0.0f);

    EXPECT_TRUE(block.put(Point2f(3.0f, 3.0f), Color3f(0.5f, 0.5f, 0.5f)));
    Bitmap bitmap = block.toBitmap();
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 6; ++x) EXPECT_TRUE(isFinite(bitmap(y, x))) << x << "," << y;
    EXPECT_NEAR(bitmap(2, 2)[0], 0.5f, 1e-6f);

    // The count travels with merges and is reset by clear().
    ImageBlock image(Vector2i(6, 6), gauss.get());
    image.put(block);
    EXPECT_EQ(image.droppedSamples(), 4u);
    block.clear();
    EXPECT_EQ(block.droppedSamples(), 0u);
    EXPECT_EQ(totalWeight(block), 0.0f);
}

TEST(ImageBlock, MergingBlocksEqualsSplattingIntoOne) {
    auto gauss = makeFilter("gaussian");
    const Vector2i imageSize(20, 13);
    ImageBlock direct(imageSize, gauss.get()), merged(imageSize, gauss.get());
    BlockGenerator generator(imageSize, 8);

    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<ImageBlock> blocks;
    for (int i = 0; i < generator.blockCount(); ++i) {
        blocks.emplace_back(Vector2i(8, 8), gauss.get());
        generator.prepare(i, blocks.back());
    }
    for (int s = 0; s < 2000; ++s) {
        Point2f pos(u(rng) * imageSize.x(), u(rng) * imageSize.y());
        Color3f value(u(rng), u(rng) * 2.0f, u(rng) * 4.0f);
        direct.put(pos, value);
        // Each sample goes to the block whose inner region contains it.
        int hits = 0;
        for (ImageBlock &block : blocks) {
            Point2i o = block.offset();
            if (pos.x() >= o.x() && pos.x() < o.x() + block.size().x() && pos.y() >= o.y() &&
                pos.y() < o.y() + block.size().y()) {
                block.put(pos, value);
                ++hits;
            }
        }
        ASSERT_EQ(hits, 1);
    }
    for (const ImageBlock &block : blocks) merged.put(block);

    for (int y = -2; y < imageSize.y() + 2; ++y)
        for (int x = -2; x < imageSize.x() + 2; ++x) {
            Eigen::Array4f a = direct.pixel(x, y), b = merged.pixel(x, y);
            for (int k = 0; k < 4; ++k)
                ASSERT_NEAR(a[k], b[k], 1e-4f * std::max(1.0f, std::abs(a[k]))) << x << "," << y << "," << k;
        }
    Bitmap da = direct.toBitmap(), mb = merged.toBitmap();
    for (int y = 0; y < imageSize.y(); ++y)
        for (int x = 0; x < imageSize.x(); ++x)
            for (int k = 0; k < 3; ++k) ASSERT_NEAR(da(y, x)[k], mb(y, x)[k], 1e-4f);
}

TEST(ImageBlock, MergeClipsToOverlap) {
    auto tent = makeFilter("tent"); // border 1
    ImageBlock image(Vector2i(4, 4), tent.get());
    ImageBlock corner(Vector2i(2, 2), tent.get());
    corner.setOffset(Point2i(3, 3)); // sticks out of the 4x4 image by one pixel plus border
    corner.put(Point2f(4.5f, 4.5f), Color3f(1, 1, 1)); // centred on a pixel outside the image
    corner.put(Point2f(3.5f, 3.5f), Color3f(2, 2, 2));
    image.put(corner);
    // Only image pixels (3..4, 3..4 incl. image border) received anything; the inner (3,3) got both.
    EXPECT_NEAR(image.pixel(3, 3)[3], 1.0f, 1e-6f);
    EXPECT_NEAR(image.pixel(3, 3)[0], 2.0f, 1e-6f);
    EXPECT_NEAR(image.pixel(4, 4)[3], 1.0f, 1e-6f); // border pixel of the image block
    EXPECT_EQ(image.pixel(2, 2)[3], 0.0f);
    EXPECT_THROW(image.pixel(5, 5), std::out_of_range);
}

// ---------------------------------------------------------------------------------------------
// BlockGenerator
// ---------------------------------------------------------------------------------------------

TEST(BlockGenerator, CoversEveryPixelExactlyOnce) {
    for (Vector2i imageSize : {Vector2i(100, 70), Vector2i(32, 32), Vector2i(1, 200), Vector2i(65, 1)}) {
        BlockGenerator generator(imageSize, 32);
        const int nx = (imageSize.x() + 31) / 32, ny = (imageSize.y() + 31) / 32;
        ASSERT_EQ(generator.blockCount(), nx * ny);
        std::vector<int> count(size_t(imageSize.x() * imageSize.y()), 0);
        ImageBlock block(Vector2i(32, 32), nullptr);
        int index = -1, handed = 0;
        while (generator.next(block, index)) {
            EXPECT_EQ(index, handed++);
            EXPECT_EQ(block.offset(), generator.blockOffset(index));
            EXPECT_EQ(block.size(), generator.blockExtent(index));
            EXPECT_LE(block.size().x(), 32);
            for (int y = 0; y < block.size().y(); ++y)
                for (int x = 0; x < block.size().x(); ++x) {
                    int px = block.offset().x() + x, py = block.offset().y() + y;
                    ASSERT_TRUE(px >= 0 && py >= 0 && px < imageSize.x() && py < imageSize.y());
                    ++count[size_t(py * imageSize.x() + px)];
                }
        }
        EXPECT_EQ(handed, generator.blockCount());
        for (size_t i = 0; i < count.size(); ++i) ASSERT_EQ(count[i], 1) << "pixel " << i;
        EXPECT_FALSE(generator.next(block)); // stays exhausted
    }
}

TEST(BlockGenerator, OrderIsDeterministicSpiralFromCentre) {
    BlockGenerator a(Vector2i(160, 96), 32), b(Vector2i(160, 96), 32); // 5 x 3 blocks
    ASSERT_EQ(a.blockCount(), 15);
    EXPECT_EQ(a.blockOffset(0), Point2i(64, 32)); // central block first
    EXPECT_EQ(a.blockOffset(1), Point2i(96, 32)); // then right, down, left, ...
    EXPECT_EQ(a.blockOffset(2), Point2i(96, 64));
    EXPECT_EQ(a.blockOffset(3), Point2i(64, 64));
    for (int i = 0; i < a.blockCount(); ++i) EXPECT_EQ(a.blockOffset(i), b.blockOffset(i));

    // Handing out again after reset() repeats the same sequence.
    std::vector<Point2i> first, second;
    ImageBlock block(Vector2i(32, 32), nullptr);
    while (a.next(block)) first.push_back(block.offset());
    a.reset();
    while (a.next(block)) second.push_back(block.offset());
    EXPECT_EQ(first, second);
}

TEST(BlockGenerator, ConcurrentNextHandsOutEachBlockOnce) {
    BlockGenerator generator(Vector2i(300, 200), 16); // 19 x 13 blocks
    std::vector<std::vector<int>> claimed(2);
    std::vector<std::thread> threads;
    for (int t = 0; t < 2; ++t)
        threads.emplace_back([&, t] {
            ImageBlock block(Vector2i(16, 16), nullptr);
            int index;
            while (generator.next(block, index)) claimed[size_t(t)].push_back(index);
        });
    for (auto &thread : threads) thread.join();
    std::multiset<int> all(claimed[0].begin(), claimed[0].end());
    all.insert(claimed[1].begin(), claimed[1].end());
    ASSERT_EQ(int(all.size()), generator.blockCount());
    int expected = 0;
    for (int index : all) EXPECT_EQ(index, expected++);
}

TEST(BlockGenerator, RejectsInvalidSizes) {
    EXPECT_THROW(BlockGenerator(Vector2i(10, 10), 0), NoriException);
    EXPECT_THROW(BlockGenerator(Vector2i(-1, 10), 8), NoriException);
    EXPECT_EQ(BlockGenerator(Vector2i(0, 10), 8).blockCount(), 0);
}

/// Render a fake image with per-block random samples on \p threads threads, merging in block order.
static Bitmap renderWithThreads(int threads) {
    auto gauss = makeFilter("gaussian");
    const Vector2i imageSize(75, 50);
    BlockGenerator generator(imageSize, 16);
    std::vector<std::unique_ptr<ImageBlock>> results(size_t(generator.blockCount()));
    tbb::task_arena arena(threads);
    arena.execute([&] {
        // Blocks are reused per thread, so stale content from an earlier block would show up.
        tbb::enumerable_thread_specific<ImageBlock> scratch([&] { return ImageBlock(Vector2i(16, 16), gauss.get()); });
        tbb::parallel_for(0, generator.blockCount(), [&](int) {
            ImageBlock &block = scratch.local();
            int index;
            if (!generator.next(block, index)) return;
            std::mt19937 rng(unsigned(index) * 7919u + 1u); // samples depend on the block only
            std::uniform_real_distribution<float> u(0.0f, 1.0f);
            for (int s = 0; s < 200; ++s)
                block.put(Point2f(block.offset().x() + u(rng) * block.size().x(),
                                  block.offset().y() + u(rng) * block.size().y()),
                          Color3f(u(rng), u(rng), u(rng)));
            results[size_t(index)] = std::make_unique<ImageBlock>(block);
        });
    });
    ImageBlock image(imageSize, gauss.get());
    for (const auto &block : results) image.put(*block); // fixed order: block index
    return image.toBitmap();
}

TEST(BlockGenerator, MergingInIndexOrderIsBitIdenticalForAnyThreadCount) {
    Bitmap one = renderWithThreads(1), two = renderWithThreads(2), four = renderWithThreads(4);
    ASSERT_EQ(one.pixels().size(), two.pixels().size());
    EXPECT_EQ(std::memcmp(one.pixels().data(), two.pixels().data(), one.pixels().size() * sizeof(Color3f)), 0);
    EXPECT_EQ(std::memcmp(one.pixels().data(), four.pixels().data(), one.pixels().size() * sizeof(Color3f)), 0);
}

// ---------------------------------------------------------------------------------------------
// Bitmap I/O
// ---------------------------------------------------------------------------------------------

TEST(Bitmap, StorageIsRowMajor) {
    Bitmap bitmap(3, 2);
    EXPECT_EQ(bitmap.width(), 3);
    EXPECT_EQ(bitmap.height(), 2);
    bitmap.coeffRef(1, 2) = Color3f(1, 2, 3);
    EXPECT_TRUE((bitmap.pixels()[5] == Color3f(1, 2, 3)).all());
    EXPECT_TRUE((bitmap(0, 0) == 0.0f).all());
    EXPECT_THROW(Bitmap(-1, 2), NoriException);
}

TEST_F(ImageFiles, ExrRoundTripIsExact) {
    Bitmap bitmap = noiseBitmap(7, 5, 42);
    bitmap(0, 0) = Color3f(1e30f, -3.5f, 1e-40f); // huge, negative, denormal
    bitmap(4, 6) = Color3f(0.1f, 1.0f / 3.0f, 65504.0f);
    const std::string path = (m_dir / "out.exr").string();
    bitmap.saveEXR(path);
    Bitmap loaded = Bitmap::loadEXR(path);
    ASSERT_EQ(loaded.width(), 7);
    ASSERT_EQ(loaded.height(), 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            for (int k = 0; k < 3; ++k) ASSERT_EQ(loaded(y, x)[k], bitmap(y, x)[k]) << x << "," << y << "," << k;
    EXPECT_EQ(listDirectory(m_dir), std::vector<std::string>{"out.exr"}); // no temporary left behind
}

TEST_F(ImageFiles, PngHasExpectedSRGBBytes) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    Bitmap bitmap(3, 2);
    bitmap(0, 0) = Color3f(0.0f, 1.0f, 0.5f);
    bitmap(0, 1) = Color3f(0.18f, 0.001f, 0.05f);
    bitmap(0, 2) = Color3f(2.0f, -1.0f, nan);
    bitmap(1, 0) = Color3f(0.0031308f, 0.04f, 0.9f);
    bitmap(1, 1) = Color3f(Infinity, -Infinity, 0.2f);
    bitmap(1, 2) = Color3f(1.0f, 1.0f, 1.0f);
    const std::string path = (m_dir / "out.png").string();
    bitmap.savePNG(path);

    int w = 0, h = 0, channels = 0;
    unsigned char *data = stbi_load(path.c_str(), &w, &h, &channels, 3);
    ASSERT_NE(data, nullptr) << stbi_failure_reason();
    std::vector<unsigned char> bytes(data, data + w * h * 3);
    stbi_image_free(data);
    ASSERT_EQ(w, 3);
    ASSERT_EQ(h, 2);
    EXPECT_EQ(channels, 3);
    // Independently computed: round(255 * sRGB(v)) with sRGB(v) = 12.92 v (v <= 0.0031308),
    // 1.055 v^(1/2.4) - 0.055 otherwise, clamped to [0, 1]; NaN -> 0.
    const std::vector<unsigned char> expected = {
        0, 255, 188,  118, 3, 63,  255, 0, 0,  //
        10, 56, 243,  255, 0, 124, 255, 255, 255,
    };
    EXPECT_EQ(bytes, expected);
}

TEST_F(ImageFiles, WriteIntoMissingDirectoryThrowsAndLeavesNoFile) {
    Bitmap bitmap = noiseBitmap(4, 4, 1);
    const fs::path missing = m_dir / "missing";
    for (const std::string name : {"out.exr", "out.png"}) {
        const std::string path = (missing / name).string();
        try {
            if (name == "out.exr")
                bitmap.saveEXR(path);
            else
                bitmap.savePNG(path);
            ADD_FAILURE() << "writing " << path << " did not throw";
        } catch (const NoriException &e) {
            EXPECT_EQ(std::string(e.what()).rfind(path + ": cannot write", 0), 0u) << e.what();
        }
        EXPECT_FALSE(fs::exists(missing));
    }
    EXPECT_TRUE(listDirectory(m_dir).empty());
}

TEST_F(ImageFiles, FailedWriteLeavesExistingTargetUntouched) {
    const std::string original(4096, 'x');
    Bitmap bitmap = noiseBitmap(64, 64, 7); // noise: both encodings are far larger than the limit
    for (const std::string name : {"out.png", "out.exr"}) {
        const fs::path target = m_dir / name;
        { std::ofstream(target, std::ios::binary) << original; }
        bool threw = false;
        {
            // The existing file is not written to, so the limit only hits the new data.
            FileSizeLimit limit(1024);
            ASSERT_TRUE(limit.ok());
            try {
                if (name == "out.exr")
                    bitmap.saveEXR(target.string());
                else
                    bitmap.savePNG(target.string());
            } catch (const NoriException &e) {
                threw = true;
                EXPECT_EQ(std::string(e.what()).rfind(target.string() + ": cannot write", 0), 0u)
                    << e.what();
            }
        }
        EXPECT_TRUE(threw) << name;
        EXPECT_EQ(readFile(target), original) << name;
        EXPECT_EQ(listDirectory(m_dir), std::vector<std::string>{name}) << "temporary file left behind";
        fs::remove(target);
    }
}

TEST_F(ImageFiles, FailedRenameLeavesNoTemporary) {
    // The target is a non-empty directory: writing the data works, the final rename cannot.
    const fs::path target = m_dir / "out.png";
    fs::create_directories(target / "keep");
    EXPECT_THROW(noiseBitmap(4, 4, 3).savePNG(target.string()), NoriException);
    EXPECT_TRUE(fs::is_directory(target / "keep"));
    EXPECT_EQ(listDirectory(m_dir), std::vector<std::string>{"out.png"});
}

TEST_F(ImageFiles, SuccessfulWriteReplacesExistingFile) {
    const fs::path target = m_dir / "out.exr";
    { std::ofstream(target, std::ios::binary) << "old content"; }
    Bitmap bitmap = noiseBitmap(5, 3, 9);
    bitmap.saveEXR(target.string());
    Bitmap loaded = Bitmap::loadEXR(target.string());
    ASSERT_EQ(loaded.width(), 5);
    EXPECT_TRUE((loaded(2, 4) == bitmap(2, 4)).all());
    EXPECT_EQ(listDirectory(m_dir), std::vector<std::string>{"out.exr"});
}

TEST_F(ImageFiles, ErrorsOnEmptyImagesAndUnreadableFiles) {
    EXPECT_THROW(Bitmap(0, 0).savePNG((m_dir / "empty.png").string()), NoriException);
    EXPECT_THROW(Bitmap(0, 3).saveEXR((m_dir / "empty.exr").string()), NoriException);
    EXPECT_TRUE(listDirectory(m_dir).empty());
    const std::string missing = (m_dir / "nope.exr").string();
    try {
        Bitmap::loadEXR(missing);
        ADD_FAILURE() << "loading a missing file did not throw";
    } catch (const NoriException &e) {
        EXPECT_EQ(std::string(e.what()).rfind(missing + ": cannot read image: ", 0), 0u) << e.what();
    }
    { std::ofstream(m_dir / "garbage.exr") << "not an exr file"; }
    EXPECT_THROW(Bitmap::loadEXR((m_dir / "garbage.exr").string()), NoriException);
}
