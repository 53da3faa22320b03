// Impostor atlas packing: halves mipped on the CPU, then interleaved into (colour, normal) texel pairs.
#include "systems/render/impostor_packing.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {

std::vector<uint8_t> downsample_rgba8(const std::vector<uint8_t>& src, uint32_t sw, uint32_t sh) {
    const uint32_t dw = std::max(sw / 2, 1u), dh = std::max(sh / 2, 1u);
    std::vector<uint8_t> dst(size_t{dw} * dh * 4);
    // Source coordinate of a destination texel centre, minus half a texel: the bilinear footprint's corner.
    auto axis = [](uint32_t i, uint32_t s, uint32_t d, uint32_t& i0, uint32_t& i1, float& f) {
        const float u = (float(i) + 0.5f) * float(s) / float(d) - 0.5f;
        const float fl = std::floor(u);
        f = u - fl;
        const auto last = static_cast<int64_t>(s) - 1;
        i0 = static_cast<uint32_t>(std::clamp<int64_t>(static_cast<int64_t>(fl), 0, last));
        i1 = static_cast<uint32_t>(std::clamp<int64_t>(static_cast<int64_t>(fl) + 1, 0, last));
    };
    for (uint32_t y = 0; y < dh; ++y) {
        uint32_t y0 = 0, y1 = 0;
        float fy = 0.0f;
        axis(y, sh, dh, y0, y1, fy);
        for (uint32_t x = 0; x < dw; ++x) {
            uint32_t x0 = 0, x1 = 0;
            float fx = 0.0f;
            axis(x, sw, dw, x0, x1, fx);
            for (uint32_t c = 0; c < 4; ++c) {
                auto at = [&](uint32_t xx, uint32_t yy) { return float(src[(size_t{yy} * sw + xx) * 4 + c]); };
                const float top = at(x0, y0) + (at(x1, y0) - at(x0, y0)) * fx;
                const float bottom = at(x0, y1) + (at(x1, y1) - at(x0, y1)) * fx;
                dst[(size_t{y} * dw + x) * 4 + c] = static_cast<uint8_t>(std::lround(top + (bottom - top) * fy));
            }
        }
    }
    return dst;
}

PackedImpostorAtlas pack_impostor_atlas(const TextureImage& image) {
    assert(image.width > 0 && image.height > 0 && image.height % 2 == 0);
    assert(image.rgba.size() == size_t{image.width} * image.height * 4);
    PackedImpostorAtlas out;
    out.width = image.width;
    out.height = image.height / 2;
    out.levels = 1;
    for (uint32_t s = std::max(out.width, out.height); s > 1; s /= 2) ++out.levels;
    const size_t half_bytes = size_t{out.width} * out.height * 4;
    std::vector<uint8_t> colour(image.rgba.begin(), image.rgba.begin() + static_cast<std::ptrdiff_t>(half_bytes));
    std::vector<uint8_t> normal(image.rgba.begin() + static_cast<std::ptrdiff_t>(half_bytes), image.rgba.end());
    size_t total = 0;
    for (uint32_t m = 0; m < out.levels; ++m)
        total += size_t{std::max(out.width >> m, 1u)} * std::max(out.height >> m, 1u);
    out.texels.reserve(2 * total);
    uint32_t w = out.width, h = out.height;
    auto word = [](const std::vector<uint8_t>& v, size_t i) {
        return uint32_t{v[4 * i]} | uint32_t{v[4 * i + 1]} << 8 | uint32_t{v[4 * i + 2]} << 16 | uint32_t{v[4 * i + 3]} << 24;
    };
    for (uint32_t m = 0; m < out.levels; ++m) {
        if (m > 0) {
            colour = downsample_rgba8(colour, w, h);
            normal = downsample_rgba8(normal, w, h);
            w = std::max(w / 2, 1u);
            h = std::max(h / 2, 1u);
        }
        for (size_t i = 0; i < size_t{w} * h; ++i) {
            out.texels.push_back(word(colour, i));
            out.texels.push_back(word(normal, i));
        }
    }
    return out;
}

}  // namespace aloha
