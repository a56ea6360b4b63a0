/// \file block.cpp
/// \brief ImageBlock (filtered sample accumulation) and BlockGenerator (deterministic tiling).
#include <nori/block.h>
#include <nori/rfilter.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nori {

// ---------------------------------------------------------------------------------------------
// ImageBlock
// ---------------------------------------------------------------------------------------------

ImageBlock::ImageBlock(const Vector2i &size, const ReconstructionFilter *filter) {
    m_radius = filter ? filter->radius() : 0.5f;
    if (!std::isfinite(m_radius) || m_radius <= 0.0f)
        throw NoriException("ImageBlock: invalid filter radius {}", m_radius);
    // A sample inside the inner region reaches pixels whose centre is within the radius, i.e. up to
    // ceil(radius - 0.5) pixels beyond the inner edge (given the half-open footprint rule).
    m_border = std::max(0, int(std::ceil(m_radius - 0.5f)));
    // Tabulate once: evaluating exp()/polynomials for every pixel of every sample is wasteful.
    for (int i = 0; i <= FilterResolution; ++i)
        m_table[i] = filter ? filter->eval(m_radius * float(i) / float(FilterResolution)) : 1.0f;
    m_tableScale = float(FilterResolution) / m_radius;
    setSize(size);
}

void ImageBlock::setSize(const Vector2i &size) {
    if (size.x() < 0 || size.y() < 0) throw NoriException("ImageBlock: invalid size {}x{}", size.x(), size.y());
    m_size = size;
    m_storageWidth = size.x() + 2 * m_border;
    m_storageHeight = size.y() + 2 * m_border;
    m_data.assign(size_t(m_storageWidth) * size_t(m_storageHeight) * 4, 0.0f);
    m_dropped = 0;
}

void ImageBlock::clear() {
    std::fill(m_data.begin(), m_data.end(), 0.0f);
    m_dropped = 0;
}

float ImageBlock::filterWeight(float x) const {
    float ax = std::abs(x);
    if (!(ax <= m_radius)) return 0.0f; // also rejects NaN
    // ax * (N / r) may round slightly above N when ax == r; clamp to stay inside the table.
    float f = std::min(ax * m_tableScale, float(FilterResolution));
    int i = std::min(int(f), FilterResolution - 1);
    float t = f - float(i);
    return m_table[i] + t * (m_table[i + 1] - m_table[i]);
}

bool ImageBlock::put(const Point2f &pos, const Color3f &value) {
    if (!isFinite(value) || !std::isfinite(pos.x()) || !std::isfinite(pos.y())) {
        ++m_dropped; // the caller decides whether to warn; one bad sample must not poison the image
        return false;
    }
    // Pixels i with -r <= pos - (i + 0.5) < r, i.e. floor(pos - 0.5 - r) < i <= floor(pos - 0.5 + r).
    // Computed in double and clipped before converting, so far-away samples cannot overflow an int.
    const double r = double(m_radius);
    const double cx = double(pos.x()) - 0.5, cy = double(pos.y()) - 0.5;
    const double minX = m_offset.x() - m_border, maxX = minX + m_storageWidth - 1;
    const double minY = m_offset.y() - m_border, maxY = minY + m_storageHeight - 1;
    const double loX = std::max(std::floor(cx - r) + 1.0, minX), hiX = std::min(std::floor(cx + r), maxX);
    const double loY = std::max(std::floor(cy - r) + 1.0, minY), hiY = std::min(std::floor(cy + r), maxY);
    if (loX > hiX || loY > hiY) return true; // entirely outside this block: accepted, nothing to add

    const int x0 = int(loX), x1 = int(hiX), y0 = int(loY), y1 = int(hiY);
    // Separable filter: evaluate each axis once, then take products.
    float weightsX[64], weightsY[64];
    std::vector<float> heapX, heapY; // only for unusually wide filters
    float *wx = weightsX, *wy = weightsY;
    if (x1 - x0 + 1 > 64) { heapX.resize(size_t(x1 - x0 + 1)); wx = heapX.data(); }
    if (y1 - y0 + 1 > 64) { heapY.resize(size_t(y1 - y0 + 1)); wy = heapY.data(); }
    for (int x = x0; x <= x1; ++x) wx[x - x0] = filterWeight(pos.x() - (float(x) + 0.5f));
    for (int y = y0; y <= y1; ++y) wy[y - y0] = filterWeight(pos.y() - (float(y) + 0.5f));

    const int originX = m_offset.x() - m_border, originY = m_offset.y() - m_border;
    for (int y = y0; y <= y1; ++y) {
        const float weightY = wy[y - y0];
        float *row = &m_data[storageIndex(x0 - originX, y - originY)];
        for (int x = x0; x <= x1; ++x, row += 4) {
            const float w = wx[x - x0] * weightY;
            row[0] += value[0] * w;
            row[1] += value[1] * w;
            row[2] += value[2] * w;
            row[3] += w;
        }
    }
    return true;
}

void ImageBlock::put(const ImageBlock &other) {
    // Overlap of the two storage rectangles (borders included), in image pixel coordinates.
    const int thisX = m_offset.x() - m_border, thisY = m_offset.y() - m_border;
    const int otherX = other.m_offset.x() - other.m_border, otherY = other.m_offset.y() - other.m_border;
    const int x0 = std::max(thisX, otherX), x1 = std::min(thisX + m_storageWidth, otherX + other.m_storageWidth);
    const int y0 = std::max(thisY, otherY), y1 = std::min(thisY + m_storageHeight, otherY + other.m_storageHeight);
    m_dropped += other.m_dropped;
    if (x0 >= x1 || y0 >= y1) return;
    for (int y = y0; y < y1; ++y) {
        float *dst = &m_data[storageIndex(x0 - thisX, y - thisY)];
        const float *src = &other.m_data[other.storageIndex(x0 - otherX, y - otherY)];
        for (int k = 0; k < (x1 - x0) * 4; ++k) dst[k] += src[k];
    }
}

Bitmap ImageBlock::toBitmap() const {
    Bitmap result(m_size);
    for (int y = 0; y < m_size.y(); ++y)
        for (int x = 0; x < m_size.x(); ++x) {
            const float *p = &m_data[storageIndex(x + m_border, y + m_border)];
            // Negative-lobed filters (Mitchell) can give negative weights; only exact zero means "no data".
            result(y, x) = p[3] != 0.0f ? Color3f(p[0] / p[3], p[1] / p[3], p[2] / p[3]) : Color3f::Zero();
        }
    return result;
}

Eigen::Array4f ImageBlock::pixel(int x, int y) const {
    const int sx = x + m_border, sy = y + m_border;
    if (sx < 0 || sy < 0 || sx >= m_storageWidth || sy >= m_storageHeight)
        throw std::out_of_range(fmt::format("ImageBlock::pixel({}, {}) is outside the block", x, y));
    const float *p = &m_data[storageIndex(sx, sy)];
    return Eigen::Array4f(p[0], p[1], p[2], p[3]);
}

// ---------------------------------------------------------------------------------------------
// BlockGenerator
// ---------------------------------------------------------------------------------------------

BlockGenerator::BlockGenerator(const Vector2i &imageSize, int blockSize)
    : m_imageSize(imageSize), m_blockSize(blockSize) {
    if (blockSize <= 0) throw NoriException("BlockGenerator: block size must be positive (got {})", blockSize);
    if (imageSize.x() < 0 || imageSize.y() < 0)
        throw NoriException("BlockGenerator: invalid image size {}x{}", imageSize.x(), imageSize.y());
    const int nx = (imageSize.x() + blockSize - 1) / blockSize;
    const int ny = (imageSize.y() + blockSize - 1) / blockSize;
    const size_t total = size_t(nx) * size_t(ny);
    m_offsets.reserve(total);
    if (total == 0) return;

    // Square spiral over the block grid: right 1, down 1, left 2, up 2, right 3, ... starting at the
    // central block; cells outside the grid are skipped. A square spiral visits every lattice cell
    // exactly once, so each block appears once and the order depends only on (nx, ny).
    const int dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
    int x = (nx - 1) / 2, y = (ny - 1) / 2;
    auto visit = [&](int bx, int by) {
        if (bx >= 0 && by >= 0 && bx < nx && by < ny) m_offsets.emplace_back(bx * blockSize, by * blockSize);
    };
    visit(x, y);
    int direction = 0;
    for (int length = 1; m_offsets.size() < total; ++length)
        for (int leg = 0; leg < 2; ++leg, direction = (direction + 1) % 4)
            for (int step = 0; step < length; ++step) {
                x += dx[direction];
                y += dy[direction];
                visit(x, y);
            }
}

Point2i BlockGenerator::blockOffset(int index) const {
    if (index < 0 || index >= blockCount())
        throw std::out_of_range(fmt::format("BlockGenerator: block index {} out of range", index));
    return m_offsets[size_t(index)];
}

Vector2i BlockGenerator::blockExtent(int index) const {
    const Point2i offset = blockOffset(index);
    return Vector2i(std::min(m_blockSize, m_imageSize.x() - offset.x()),
                    std::min(m_blockSize, m_imageSize.y() - offset.y()));
}

void BlockGenerator::prepare(int index, ImageBlock &block) const {
    const Vector2i extent = blockExtent(index);
    block.setOffset(blockOffset(index));
    if (block.size() != extent)
        block.setSize(extent); // also clears
    else
        block.clear();
}

bool BlockGenerator::next(ImageBlock &block, int &index) {
    // Check first so that idle threads polling an exhausted generator do not grow the counter.
    if (m_next.load(std::memory_order_relaxed) >= blockCount()) return false;
    const int claimed = m_next.fetch_add(1, std::memory_order_relaxed);
    if (claimed >= blockCount()) return false;
    index = claimed;
    prepare(claimed, block);
    return true;
}

bool BlockGenerator::next(ImageBlock &block) {
    int index;
    return next(block, index);
}

} // namespace nori
