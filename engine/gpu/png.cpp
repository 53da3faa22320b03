#include "engine/gpu/png.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace aloha::gpu {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors through longjmp; the message is captured here first.
struct PngErrorState {
    char message[256] = "unknown libpng error";
};

void on_png_error(png_structp png, png_const_charp msg) {
    auto* st = static_cast<PngErrorState*>(png_get_error_ptr(png));
    std::snprintf(st->message, sizeof st->message, "%s", msg);
    png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

}  // namespace

Status write_png(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
    if (width == 0 || height == 0 || rgba.size() != size_t(width) * height * 4)
        return make_error(path, "write_png: expected " + std::to_string(size_t(width) * height * 4) +
                                    " bytes for " + std::to_string(width) + "x" + std::to_string(height) +
                                    " RGBA, got " + std::to_string(rgba.size()));
    FilePtr f(std::fopen(path.c_str(), "wb"));
    if (!f) {
        Error e = make_error(path, std::string("cannot open for writing: ") + std::strerror(errno));
        e.code = errno;
        return e;
    }
    PngErrorState st;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &st, on_png_error, on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        return make_error(path, "libpng: out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return make_error(path, std::string("libpng: ") + st.message);
    }
    png_init_io(png, f.get());
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (uint32_t y = 0; y < height; ++y)
        png_write_row(png, const_cast<png_bytep>(rgba.data() + size_t(y) * width * 4));
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    if (std::fflush(f.get()) != 0) return make_error(path, "write failed (disk full?)");
    return {};
}

Result<Rgba8Image> read_png(const std::string& path) {
    FilePtr f(std::fopen(path.c_str(), "rb"));
    if (!f) {
        Error e = make_error(path, std::string("cannot open: ") + std::strerror(errno));
        e.code = errno;
        return e;
    }
    unsigned char sig[8] = {};
    if (std::fread(sig, 1, 8, f.get()) != 8 || png_sig_cmp(sig, 0, 8) != 0)
        return make_error(path, "not a PNG file (bad signature)");
    PngErrorState st;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &st, on_png_error, on_png_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_read_struct(&png, &info, nullptr);
        return make_error(path, "libpng: out of memory");
    }
    Rgba8Image img;
    std::vector<png_bytep> rows;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return make_error(path, std::string("corrupt PNG: ") + st.message);
    }
    png_init_io(png, f.get());
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    // Normalise every colour type / depth to 8-bit RGBA.
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
    png_read_update_info(png, info);
    img.width = png_get_image_width(png, info);
    img.height = png_get_image_height(png, info);
    if (png_get_rowbytes(png, info) != size_t(img.width) * 4) {
        png_destroy_read_struct(&png, &info, nullptr);
        return make_error(path, "unsupported PNG layout after conversion to RGBA8");
    }
    img.pixels.resize(size_t(img.width) * img.height * 4);
    rows.resize(img.height);
    for (uint32_t y = 0; y < img.height; ++y) rows[y] = img.pixels.data() + size_t(y) * img.width * 4;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return img;
}

}  // namespace aloha::gpu
