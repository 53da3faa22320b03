#include "host/tool/image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <unordered_map>

namespace aloha::tool {

double psnr_db(std::span<const uint8_t> a, std::span<const uint8_t> b) {
    const size_t bytes = std::min(a.size(), b.size()) / 4 * 4;
    double se = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < bytes; i += 4)
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(a[i + c]) - double(b[i + c]);
            se += d * d;
            ++n;
        }
    if (n == 0 || se == 0.0) return 99.0;
    return 10.0 * std::log10(255.0 * 255.0 / (se / double(n)));
}

double change_map(std::span<const uint8_t> now, std::span<const uint8_t> before, std::vector<uint16_t>& out) {
    out.clear();
    if (now.empty() || now.size() != before.size()) return 0.0;
    out.resize(now.size() / 4);
    uint64_t total = 0;
    for (size_t p = 0; p < out.size(); ++p) {
        int sum = 0;
        for (size_t c = 0; c < 3; ++c) sum += std::abs(int(now[4 * p + c]) - int(before[4 * p + c]));
        out[p] = static_cast<uint16_t>(sum);
        total += uint64_t(sum);
    }
    return double(total) / (255.0 * 3.0 * double(out.size()));
}

double error_change(std::span<const uint8_t> lod, std::span<const uint8_t> reference, std::span<const uint8_t> lod_before,
                    std::span<const uint8_t> reference_before, std::vector<uint16_t>& out) {
    out.clear();
    const size_t bytes = lod.size();
    if (bytes == 0 || reference.size() != bytes || lod_before.size() != bytes || reference_before.size() != bytes) return 0.0;
    out.resize(bytes / 4);
    uint64_t total = 0;
    for (size_t p = 0; p < out.size(); ++p) {
        int sum = 0;
        for (size_t c = 0; c < 3; ++c) {
            const size_t i = 4 * p + c;
            const int now = int(lod[i]) - int(reference[i]);
            const int before = int(lod_before[i]) - int(reference_before[i]);
            sum += std::abs(now - before);
        }
        out[p] = static_cast<uint16_t>(sum);
        total += uint64_t(sum);
    }
    return double(total) / (255.0 * 3.0 * double(out.size()));
}

namespace {

// The most common RGB of `image` (packed r | g << 8 | b << 16), from every 7th pixel.
uint32_t background_of(std::span<const uint8_t> image) {
    std::unordered_map<uint32_t, uint32_t> counts;
    uint32_t best = 0, best_count = 0;
    for (size_t p = 0; p < image.size() / 4; p += 7) {
        const uint32_t rgb = uint32_t(image[4 * p]) | uint32_t(image[4 * p + 1]) << 8 | uint32_t(image[4 * p + 2]) << 16;
        const uint32_t n = ++counts[rgb];
        if (n > best_count) {
            best = rgb;
            best_count = n;
        }
    }
    return best;
}

// 1 where the pixel differs from `background` by more than kSilhouetteLevels.
std::vector<uint8_t> character_mask(std::span<const uint8_t> image, uint32_t background) {
    std::vector<uint8_t> mask(image.size() / 4);
    for (size_t p = 0; p < mask.size(); ++p) {
        int d = 0;
        for (size_t c = 0; c < 3; ++c) d += std::abs(int(image[4 * p + c]) - int((background >> (8 * c)) & 0xffu));
        mask[p] = d > kSilhouetteLevels ? 1 : 0;
    }
    return mask;
}

// The mask grown by one pixel each way (a 3 x 3 maximum, rows then columns).
std::vector<uint8_t> grown(const std::vector<uint8_t>& mask, size_t width) {
    const size_t height = mask.size() / width;
    std::vector<uint8_t> rows(mask.size()), out(mask.size());
    for (size_t y = 0; y < height; ++y)
        for (size_t x = 0; x < width; ++x) {
            const size_t p = y * width + x;
            rows[p] = mask[p] | (x > 0 ? mask[p - 1] : 0) | (x + 1 < width ? mask[p + 1] : 0);
        }
    for (size_t y = 0; y < height; ++y)
        for (size_t x = 0; x < width; ++x) {
            const size_t p = y * width + x;
            out[p] = rows[p] | (y > 0 ? rows[p - width] : 0) | (y + 1 < height ? rows[p + width] : 0);
        }
    return out;
}

}  // namespace

SilhouetteCoverage silhouette_coverage(std::span<const uint8_t> image, std::span<const uint8_t> reference, uint32_t width) {
    SilhouetteCoverage out;
    if (width == 0 || image.size() != reference.size() || image.empty() || (image.size() / 4) % width != 0) return out;
    const uint32_t background = background_of(reference);
    const std::vector<uint8_t> mine = character_mask(image, background), theirs = character_mask(reference, background);
    const std::vector<uint8_t> mine_grown = grown(mine, width), theirs_grown = grown(theirs, width);
    uint64_t covered = 0, on_reference = 0;
    for (size_t p = 0; p < mine.size(); ++p) {
        out.reference_pixels += theirs[p];
        out.pixels += mine[p];
        covered += theirs[p] & mine_grown[p];
        on_reference += mine[p] & theirs_grown[p];
    }
    if (out.reference_pixels > 0) out.covered = double(covered) / double(out.reference_pixels);
    if (out.pixels > 0) out.on_reference = double(on_reference) / double(out.pixels);
    return out;
}

}  // namespace aloha::tool
