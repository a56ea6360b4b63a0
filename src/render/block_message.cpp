/// \file block_message.cpp
/// \brief BlockMessage: a fixed header followed by the block's floats.
#include "block_message.h"
#include <cstdint>
#include <cstring>

namespace nori {

namespace {

/// Marks the layout below; a process of another build would not match it.
constexpr uint32_t Magic = 0x4e424c31; // "NBL1"

struct Header {
    uint32_t magic;
    int32_t index;
    int32_t width, height, border;
    uint32_t floats;
    uint64_t cameraRays, closestHitRays, shadowRays, droppedSamples;
};

} // namespace

std::vector<char> BlockMessage::encode(int index, const ImageBlock &block, const BlockTally &tally) {
    Header header{Magic,
                  int32_t(index),
                  block.size().x(),
                  block.size().y(),
                  block.borderSize(),
                  uint32_t(block.storageSize()),
                  tally.cameraRays,
                  tally.closestHitRays,
                  tally.shadowRays,
                  tally.droppedSamples};
    std::vector<char> bytes(sizeof(Header) + block.storageSize() * sizeof(float));
    std::memcpy(bytes.data(), &header, sizeof(Header));
    std::memcpy(bytes.data() + sizeof(Header), block.storage(), block.storageSize() * sizeof(float));
    return bytes;
}

ImageBlock BlockMessage::decode(const char *bytes, size_t size, const BlockGenerator &generator,
                                const ReconstructionFilter *filter, int &index, BlockTally &tally) {
    Header header;
    if (size < sizeof(Header)) throw NoriException("block message of {} bytes is too short", size);
    std::memcpy(&header, bytes, sizeof(Header));
    if (header.magic != Magic) throw NoriException("block message with an unknown layout");
    if (header.index < 0 || header.index >= generator.blockCount())
        throw NoriException("block message for block {} of an image of {} blocks", header.index, generator.blockCount());
    ImageBlock block(Vector2i(generator.blockSize(), generator.blockSize()), filter);
    generator.prepare(header.index, block);
    if (header.width != block.size().x() || header.height != block.size().y() || header.border != block.borderSize() ||
        size_t(header.floats) != block.storageSize() || size != sizeof(Header) + block.storageSize() * sizeof(float))
        throw NoriException("block message for block {} ({}x{}, border {}) does not match this image's block "
                            "({}x{}, border {}): do all processes render the same scene?",
                            header.index, header.width, header.height, header.border, block.size().x(),
                            block.size().y(), block.borderSize());
    std::memcpy(block.storage(), bytes + sizeof(Header), block.storageSize() * sizeof(float));
    block.setDroppedSamples(header.droppedSamples);
    index = header.index;
    tally = BlockTally{header.cameraRays, header.closestHitRays, header.shadowRays, header.droppedSamples};
    return block;
}

} // namespace nori
