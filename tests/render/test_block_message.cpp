/// \file test_block_message.cpp
/// \brief BlockMessage: a block survives the trip bit for bit, and messages that do not fit the
/// image are refused.
#include "render/block_message.h"
#include <gtest/gtest.h>
#include <nori/proplist.h>
#include <nori/rfilter.h>
#include <nori/object.h>
#include <cmath>
#include <cstring>
#include <memory>

using namespace nori;

namespace {

/// A Gaussian filter (radius 2): blocks with a border of 2 pixels.
std::unique_ptr<ReconstructionFilter> gaussian() {
    std::unique_ptr<NoriObject> object =
        NoriObjectFactory::createInstance(NoriObject::EReconstructionFilter, "gaussian", PropertyList());
    return std::unique_ptr<ReconstructionFilter>(static_cast<ReconstructionFilter *>(object.release()));
}

/// Block \p index of \p generator with a few splats (some on the border) and a dropped sample.
ImageBlock filledBlock(const BlockGenerator &generator, const ReconstructionFilter *filter, int index) {
    ImageBlock block(Vector2i(32, 32), filter);
    generator.prepare(index, block);
    const Point2i o = block.offset();
    block.put(Point2f(o.x() + 0.3f, o.y() + 0.7f), Color3f(1.0f, 0.5f, 0.25f));
    block.put(Point2f(o.x() + 5.1f, o.y() + 9.9f), Color3f(0.1f, 2.0f, 3.0f));
    block.put(Point2f(o.x() + block.size().x() - 0.2f, o.y() + 1.5f), Color3f(7.0f, 0.0f, 1e-3f));
    block.put(Point2f(o.x() + 1.0f, o.y() + 1.0f), Color3f(std::nanf(""), 0.0f, 0.0f));
    return block;
}

} // namespace

TEST(BlockMessage, RoundTripIsBitExact) {
    auto filter = gaussian();
    BlockGenerator generator(Vector2i(100, 70), 32); // edge blocks are smaller
    for (int index = 0; index < generator.blockCount(); ++index) {
        SCOPED_TRACE(index);
        ImageBlock sent = filledBlock(generator, filter.get(), index);
        BlockTally tally{11, 22, 33, sent.droppedSamples()};
        std::vector<char> bytes = BlockMessage::encode(index, sent, tally);
        int received = -1;
        BlockTally back;
        ImageBlock block = BlockMessage::decode(bytes.data(), bytes.size(), generator, filter.get(), received, back);
        EXPECT_EQ(received, index);
        EXPECT_EQ(block.offset(), sent.offset());
        EXPECT_EQ(block.size(), sent.size());
        ASSERT_EQ(block.storageSize(), sent.storageSize());
        EXPECT_EQ(std::memcmp(block.storage(), sent.storage(), sent.storageSize() * sizeof(float)), 0);
        EXPECT_EQ(block.droppedSamples(), 1u);
        EXPECT_EQ(back.cameraRays, 11u);
        EXPECT_EQ(back.closestHitRays, 22u);
        EXPECT_EQ(back.shadowRays, 33u);
        EXPECT_EQ(back.droppedSamples, 1u);
    }
}

TEST(BlockMessage, MessagesThatDoNotFitTheImageAreRefused) {
    auto filter = gaussian();
    BlockGenerator generator(Vector2i(100, 70), 32);
    ImageBlock sent = filledBlock(generator, filter.get(), 0);
    std::vector<char> bytes = BlockMessage::encode(0, sent, BlockTally{});
    int index;
    BlockTally tally;
    // Another tiling (a different image size), another filter (another border), a block index
    // out of range, a truncated message, a wrong layout mark.
    EXPECT_THROW(BlockMessage::decode(bytes.data(), bytes.size(), BlockGenerator(Vector2i(20, 20), 32), filter.get(),
                                      index, tally),
                 NoriException);
    EXPECT_THROW(BlockMessage::decode(bytes.data(), bytes.size(), generator, nullptr, index, tally), NoriException);
    std::vector<char> outOfRange = BlockMessage::encode(generator.blockCount(), sent, BlockTally{});
    EXPECT_THROW(BlockMessage::decode(outOfRange.data(), outOfRange.size(), generator, filter.get(), index, tally),
                 NoriException);
    EXPECT_THROW(BlockMessage::decode(bytes.data(), bytes.size() - 4, generator, filter.get(), index, tally),
                 NoriException);
    EXPECT_THROW(BlockMessage::decode(bytes.data(), 10, generator, filter.get(), index, tally), NoriException);
    std::vector<char> badMark = bytes;
    badMark[0] ^= 0x55;
    EXPECT_THROW(BlockMessage::decode(badMark.data(), badMark.size(), generator, filter.get(), index, tally),
                 NoriException);
    // And the untouched message still decodes.
    EXPECT_NO_THROW(BlockMessage::decode(bytes.data(), bytes.size(), generator, filter.get(), index, tally));
}
