/// \file block_message.h
/// \brief A finished image block as bytes, for its trip from the process that rendered it to
/// the one that merges the image.
#pragma once

#include <nori/block.h>
#include <nori/block_exchange.h>
#include <cstddef>
#include <vector>

namespace nori {

/// \brief Encodes and decodes one rendered block: a fixed header (block index, extent, border,
/// the block's tally) and the block's accumulated (r, g, b, weight) floats, border included,
/// exactly as they are in memory. Every process runs the same build on the same kind of CPU,
/// so the floats travel in host byte order and arrive bit for bit.
class BlockMessage {
public:
    /// \brief The bytes of block \p index.
    static std::vector<char> encode(int index, const ImageBlock &block, const BlockTally &tally);

    /// \brief The block in \p bytes, checked against the tiling: the index must exist and the
    /// extent, border and size must be what \p generator and \p filter give for it. Throws
    /// NoriException otherwise (a corrupt message, or processes that render different images).
    static ImageBlock decode(const char *bytes, size_t size, const BlockGenerator &generator,
                             const ReconstructionFilter *filter, int &index, BlockTally &tally);
};

} // namespace nori
