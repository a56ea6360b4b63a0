/// Bitmap storage and its OpenEXR / PNG output.
#include <nori/bitmap.h>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <stb_image_write.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace nori {

// The EXR frame buffer and the row strides below assume tightly packed float triples.
static_assert(sizeof(Color3f) == 3 * sizeof(float), "Color3f must be three packed floats");

namespace {

[[noreturn]] void writeError(const std::string &path, const std::string &reason) {
    throw NoriException("{}: cannot write image: {}", path, reason);
}

/// Distinguishes temporary files of concurrent writes to the same path within one process.
std::atomic<unsigned> g_temporaryCounter{0};

/// Write \p bytes to \p path so that readers see either the old file or the complete new one:
/// the data goes to a temporary file in the same folder (so that rename() stays within one file
/// system and is atomic), is flushed to disk, and only then renamed over the target.
/// On failure the temporary file is removed and \p path is left as it was.
void writeFileAtomically(const std::string &path, const std::string &bytes) {
    std::string temporary =
        fmt::format("{}.tmp-{}-{}", path, long(::getpid()), g_temporaryCounter.fetch_add(1));
    // O_EXCL: never clobber (or follow a symlink planted at) an existing file of that name.
    int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) writeError(path, fmt::format("cannot create '{}': {}", temporary, std::strerror(errno)));

    auto fail = [&](const char *what, bool closeFd) {
        int error = errno;
        if (closeFd) ::close(fd);
        ::unlink(temporary.c_str());
        writeError(path, fmt::format("{} '{}': {}", what, temporary, std::strerror(error)));
    };

    const char *data = bytes.data();
    size_t remaining = bytes.size();
    while (remaining > 0) {
        ssize_t written = ::write(fd, data, remaining);
        if (written < 0) {
            if (errno == EINTR) continue;
            fail("cannot write", true);
        }
        data += written;
        remaining -= size_t(written);
    }
    // Without fsync a crash right after rename() could leave an empty file under the final name.
    if (::fsync(fd) != 0) fail("cannot flush", true);
    if (::close(fd) != 0) fail("cannot close", false);
    if (::rename(temporary.c_str(), path.c_str()) != 0) fail("cannot rename", false);
}

/// Encode \p bitmap as a float RGB OpenEXR file in memory.
std::string encodeEXR(const Bitmap &bitmap) {
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
std::string encodePNG(const Bitmap &bitmap) {
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

void Bitmap::saveEXR(const std::string &path) const {
    if (m_width == 0 || m_height == 0) writeError(path, "the image is empty");
    std::string bytes;
    try {
        bytes = encodeEXR(*this);
    } catch (const std::exception &e) {
        writeError(path, e.what());
    }
    writeFileAtomically(path, bytes);
}

void Bitmap::savePNG(const std::string &path) const {
    if (m_width == 0 || m_height == 0) writeError(path, "the image is empty");
    std::string bytes;
    try {
        bytes = encodePNG(*this);
    } catch (const std::exception &e) {
        writeError(path, e.what());
    }
    writeFileAtomically(path, bytes);
}

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
