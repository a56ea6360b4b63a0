/// \file bitmap.cpp
/// \brief Bitmap storage and its OpenEXR / PNG output.
#include <nori/bitmap.h>
#include <nori/atomic_file.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <stb_image_write.h>


namespace nori {

// The EXR frame buffer and the row strides below assume tightly packed float triples.
static_assert(sizeof(Color3f) == 3 * sizeof(float), "Color3f must be three packed floats");

namespace {

/// Encode with \p encoder; every failure names \p path.
template <typename Encoder> std::string encodeFor(const std::string &path, const Bitmap &bitmap, Encoder encoder) {
    if (bitmap.width() == 0 || bitmap.height() == 0)
        throw NoriException("{}: cannot write image: the image is empty", path);
    try {
        return encoder(bitmap);
    } catch (const std::exception &e) {
        throw NoriException("{}: cannot write image: {}", path, e.what());
    }
}

/// Encode \p bitmap as a float RGB OpenEXR file in memory.
std::string exrBytes(const Bitmap &bitmap) {
    const int width = bitmap.width(), height = bitmap.height();
    Imf::Header header(width, height);
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    header.channels().insert("G", Imf::Channel(Imf::FLOAT));
    header.channels().insert("B", Imf::Channel(Imf::FLOAT));

    // OpenEXR's Slice takes a non-const pointer even for output; the data is only read.
    char *base = reinterpret_cast<char *>(const_cast<Color3f *>(bitmap.pixels().data()));
    const size_t xStride = sizeof(Color3f), yStride = xStride * size_t(width);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("R", Imf::Slice(Imf::FLOAT, base, xStride, yStride));
    frameBuffer.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xStride, yStride));
    frameBuffer.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xStride, yStride));

    Imf::StdOSStream stream;
    {
        // The file must be destroyed (which writes the line offset table) before reading the stream.
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frameBuffer);
        file.writePixels(height);
    }
    return stream.str();
}

/// One linear component as an 8-bit sRGB value; NaN maps to 0.
unsigned char toSRGB8(float value) {
    float encoded = linearToSRGB(value);
    if (!(encoded > 0.0f)) encoded = 0.0f;
    if (encoded > 1.0f) encoded = 1.0f;
    return static_cast<unsigned char>(encoded * 255.0f + 0.5f);
}

/// Encode \p bitmap as an 8-bit RGB PNG in memory.
std::string pngBytes(const Bitmap &bitmap) {
    const int width = bitmap.width(), height = bitmap.height();
    std::vector<unsigned char> rgb(size_t(width) * size_t(height) * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Color3f &c = bitmap(y, x);
            unsigned char *out = &rgb[(size_t(y) * size_t(width) + size_t(x)) * 3];
            for (int k = 0; k < 3; ++k) out[k] = toSRGB8(c[k]);
        }
    std::string encoded;
    // stb calls the sink several times; collect everything and write the file ourselves,
    // which gives us proper error reporting and the atomic rename.
    auto sink = [](void *context, void *data, int size) {
        static_cast<std::string *>(context)->append(static_cast<const char *>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(sink, &encoded, width, height, 3, rgb.data(), width * 3))
        throw std::runtime_error("PNG encoding failed");
    return encoded;
}

} // namespace

Bitmap::Bitmap(const Vector2i &size) : Bitmap(size.x(), size.y()) {}

Bitmap::Bitmap(int width, int height) : m_width(width), m_height(height) {
    if (width < 0 || height < 0) throw NoriException("Bitmap: invalid size {}x{}", width, height);
    m_pixels.assign(size_t(width) * size_t(height), Color3f::Zero());
}

std::string Bitmap::encodeEXR(const std::string &path) const { return encodeFor(path, *this, exrBytes); }

std::string Bitmap::encodePNG(const std::string &path) const { return encodeFor(path, *this, pngBytes); }

void Bitmap::saveEXR(const std::string &path) const { AtomicFile::write(path, encodeEXR(path)); }

void Bitmap::savePNG(const std::string &path) const { AtomicFile::write(path, encodePNG(path)); }

Bitmap Bitmap::loadEXR(const std::string &path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        Bitmap result(window.max.x - window.min.x + 1, window.max.y - window.min.y + 1);

        char *base = reinterpret_cast<char *>(result.m_pixels.data());
        const size_t xStride = sizeof(Color3f), yStride = xStride * size_t(result.m_width);
        Imf::FrameBuffer frameBuffer;
        // Slice::Make shifts the base pointer by the data window origin without overflow.
        frameBuffer.insert("R", Imf::Slice::Make(Imf::FLOAT, base, window, xStride, yStride));
        frameBuffer.insert("G", Imf::Slice::Make(Imf::FLOAT, base + sizeof(float), window, xStride, yStride));
        frameBuffer.insert("B", Imf::Slice::Make(Imf::FLOAT, base + 2 * sizeof(float), window, xStride, yStride));
        file.setFrameBuffer(frameBuffer);
        file.readPixels(window.min.y, window.max.y);
        return result;
    } catch (const std::exception &e) {
        throw NoriException("{}: cannot read image: {}", path, e.what());
    }
}

} // namespace nori
