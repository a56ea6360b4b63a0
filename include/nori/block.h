/// \file block.h
/// \brief Filtered sample accumulation (ImageBlock) and deterministic image tiling (BlockGenerator).
#pragma once

#include <nori/bitmap.h>
#include <atomic>
#include <cstdint>
#include <vector>

namespace nori {

class ReconstructionFilter;

/// \brief A rectangle of image pixels that accumulates filtered samples.
///
/// The block covers image pixels [offset, offset + size) plus a border of borderSize() pixels on
/// each side, so that samples taken inside the block can spill their filter footprint into the
/// neighbours; merging blocks with put(const ImageBlock &) adds the borders where they overlap.
/// Each pixel stores (r, g, b, weight); the final colour is (r, g, b) / weight.
///
/// Coordinates: image pixel (i, j) covers [i, i + 1) x [j, j + 1), its centre is (i + 0.5, j + 0.5).
/// A sample at position p reaches pixel i along an axis when -radius <= p - (i + 0.5) < radius;
/// the half-open interval makes the box filter assign every sample to exactly one pixel.
///
/// Not thread-safe: one thread fills a block; the caller serialises merges.
class ImageBlock {
public:
    /// \brief Number of entries of the filter table over [0, radius] (plus one for the end point).
    static constexpr int FilterResolution = 32;

    /// \brief A block of \p size inner pixels at offset (0, 0), cleared. The filter is only read here
    /// (it is tabulated), so it need not outlive the block; nullptr means the box filter.
    ImageBlock(const Vector2i &size, const ReconstructionFilter *filter);

    /// \brief Place the block's inner region at image pixel \p offset.
    void setOffset(const Point2i &offset) { m_offset = offset; }
    /// \brief Image pixel of the block's inner top-left corner.
    const Point2i &offset() const { return m_offset; }
    /// \brief Resize the inner region (reallocates if needed) and clear the block.
    void setSize(const Vector2i &size);
    /// \brief Width and height of the inner region.
    const Vector2i &size() const { return m_size; }
    /// \brief Border width in pixels on each side: ceil(radius - 0.5).
    int borderSize() const { return m_border; }
    /// \brief Filter radius the block was built with.
    float filterRadius() const { return m_radius; }

    /// \brief Reset every pixel (and the dropped-sample count) to zero.
    void clear();

    /// \brief Splat a sample of \p value at continuous image position \p pos with the filter.
    /// Parts of the footprint outside the block (including its border) are clipped.
    /// \return false (and counts the sample as dropped) if \p pos or \p value is not finite.
    bool put(const Point2f &pos, const Color3f &value);

    /// \brief Add the pixels (border included) of \p other where the two blocks overlap in the image,
    /// and its dropped-sample count. Floating-point addition is not associative: to get identical
    /// images regardless of scheduling, merge blocks in a fixed order (see BlockGenerator).
    void put(const ImageBlock &other);

    /// \brief Weighted average of the inner region; pixels with zero weight are black.
    Bitmap toBitmap() const;

    /// \brief Accumulated (r, g, b, weight) of the pixel at (\p x, \p y) relative to the inner
    /// top-left corner; valid for -borderSize() <= x < size().x() + borderSize() (same for y).
    Eigen::Array4f pixel(int x, int y) const;

    /// \brief Number of samples rejected since the last clear() (non-finite value or position).
    uint64_t droppedSamples() const { return m_dropped; }
    /// \brief Set the rejected-sample count (of a block received from another process).
    void setDroppedSamples(uint64_t count) { m_dropped = count; }

    /// \brief The accumulated (r, g, b, weight) of every storage pixel, border included, row by
    /// row: storageSize() floats. This is what travels when another process renders the block.
    const float *storage() const { return m_data.data(); }
    float *storage() { return m_data.data(); }
    size_t storageSize() const { return m_data.size(); }

    /// \brief Filter weight for a 1D distance \p x from a pixel centre, from the lookup table
    /// (linear interpolation between FilterResolution + 1 samples over [0, radius]).
    float filterWeight(float x) const;

private:
    /// Index of the first float of storage pixel (sx, sy); storage includes the border.
    size_t storageIndex(int sx, int sy) const { return (size_t(sy) * size_t(m_storageWidth) + size_t(sx)) * 4; }

    Point2i m_offset = Point2i(0, 0);
    Vector2i m_size = Vector2i(0, 0);
    int m_border = 0;
    int m_storageWidth = 0, m_storageHeight = 0;
    std::vector<float> m_data; ///< (r, g, b, weight) per storage pixel, row-major.
    float m_radius = 0.5f;
    float m_tableScale = 0.0f; ///< FilterResolution / radius.
    float m_table[FilterResolution + 1] = {};
    uint64_t m_dropped = 0;
};

/// \brief Splits an image into square blocks handed out in a fixed order (a spiral starting
/// at the central block, so that interactive previews fill in from the middle).
///
/// The order depends only on the image and block sizes, so a renderer can process blocks in
/// parallel and merge them by block index to obtain bit-identical images for any thread count.
class BlockGenerator {
public:
    /// \brief Tile an image of \p imageSize (width, height) with blocks of \p blockSize pixels
    /// (the last row and column may be smaller). Throws NoriException on invalid sizes.
    explicit BlockGenerator(const Vector2i &imageSize, int blockSize = 32);

    /// \brief Total number of blocks.
    int blockCount() const { return int(m_offsets.size()); }
    /// \brief Size of the whole image.
    const Vector2i &imageSize() const { return m_imageSize; }
    /// \brief Nominal block edge length.
    int blockSize() const { return m_blockSize; }

    /// \brief Image offset of block \p index (0 <= index < blockCount()).
    Point2i blockOffset(int index) const;
    /// \brief Size of block \p index (smaller than blockSize() at the right and bottom edges).
    Vector2i blockExtent(int index) const;
    /// \brief Set \p block to the offset and size of block \p index and clear it.
    void prepare(int index, ImageBlock &block) const;

    /// \brief Thread-safe: claim the next block in order, prepare \p block for it and store its
    /// index in \p index. Returns false when every block has been handed out.
    bool next(ImageBlock &block, int &index);
    /// \brief Same as next(block, index) without reporting the index.
    bool next(ImageBlock &block);
    /// \brief Hand out the blocks again from the first one (not concurrently with next()).
    void reset() { m_next.store(0); }

private:
    Vector2i m_imageSize;
    int m_blockSize;
    std::vector<Point2i> m_offsets; ///< Block offsets in hand-out order.
    std::atomic<int> m_next{0};
};

} // namespace nori
