/// \file bitmap.h
/// \brief A linear RGB image with atomic OpenEXR and PNG output.
#pragma once

#include <nori/color.h>
#include <vector>

namespace nori {

/// \brief W x H linear RGB pixels stored row-major (pixel (y, x) at index y * width + x).
class Bitmap {
public:
    /// \brief An image of \p size (width, height), every pixel black. Throws on negative sizes.
    explicit Bitmap(const Vector2i &size = Vector2i(0, 0));
    /// \brief An image of \p width x \p height, every pixel black. Throws on negative sizes.
    Bitmap(int width, int height);

    /// \brief Number of columns.
    int width() const { return m_width; }
    /// \brief Number of rows.
    int height() const { return m_height; }
    /// \brief (width, height).
    Vector2i size() const { return Vector2i(m_width, m_height); }

    /// \brief Mutable pixel in row \p y, column \p x (no bounds check in release builds).
    Color3f &coeffRef(int y, int x) { return m_pixels[index(y, x)]; }
    /// \brief Pixel in row \p y, column \p x.
    const Color3f &coeff(int y, int x) const { return m_pixels[index(y, x)]; }
    /// \brief Mutable pixel in row \p y, column \p x.
    Color3f &operator()(int y, int x) { return m_pixels[index(y, x)]; }
    /// \brief Pixel in row \p y, column \p x.
    const Color3f &operator()(int y, int x) const { return m_pixels[index(y, x)]; }
    /// \brief All pixels, row-major.
    const std::vector<Color3f> &pixels() const { return m_pixels; }

    /// \brief Write linear RGB as 32-bit float channels R, G, B (lossless ZIP compression).
    /// Atomic: the data goes to a temporary file in the same folder that is then renamed over
    /// \p path. Throws NoriException("PATH: cannot write..."); on failure \p path is untouched.
    void saveEXR(const std::string &path) const;

    /// \brief Write 8-bit sRGB (values clamped to [0, 1] after encoding), atomically like saveEXR().
    void savePNG(const std::string &path) const;

    /// \brief The bytes saveEXR() writes; \p path only names the file in error messages.
    std::string encodeEXR(const std::string &path) const;
    /// \brief The bytes savePNG() writes; \p path only names the file in error messages.
    std::string encodePNG(const std::string &path) const;

    /// \brief Read the R, G, B channels of an OpenEXR file (missing channels read as zero).
    /// Throws NoriException("PATH: cannot read image: reason").
    static Bitmap loadEXR(const std::string &path);

private:
    size_t index(int y, int x) const {
        eigen_assert(x >= 0 && x < m_width && y >= 0 && y < m_height);
        return size_t(y) * size_t(m_width) + size_t(x);
    }

    int m_width = 0, m_height = 0;
    std::vector<Color3f> m_pixels;
};

} // namespace nori
