#include "host/tool/image_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

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

}  // namespace aloha::tool
