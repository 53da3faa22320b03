#include "systems/lod/occlusion.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace aloha {

void OcclusionGrid::resize(glm::vec2 viewport_px, float cell_px, float body_cell_px) {
    width = std::max(1, static_cast<int>(std::ceil(viewport_px.x / cell_px)));
    height = std::max(1, static_cast<int>(std::ceil(viewport_px.y / cell_px)));
    depth.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
    body_width = std::max(1, static_cast<int>(std::ceil(viewport_px.x / body_cell_px)));
    body_height = std::max(1, static_cast<int>(std::ceil(viewport_px.y / body_cell_px)));
    body.resize(static_cast<size_t>(body_width) * static_cast<size_t>(body_height));
}

bool OcclusionJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string m) {
        ok = false;
        if (errors) errors->push_back("OcclusionJob: " + std::move(m));
    };
    if (attributes.size() != transforms.size()) fail("attributes size differs from transforms");
    if (!bounds.empty() && bounds.size() != transforms.size()) fail("bounds size differs from transforms (and is not empty)");
    if (!geom.empty() && geom.size() != transforms.size()) fail("geom size differs from transforms (and is not empty)");
    if (!(params.enter_margin_px >= 0.0f)) fail("enter_margin_px must be >= 0");
    if (grid == nullptr) fail("needs a grid (scratch)");
    if (!(params.cell_px >= 1.0f)) fail("cell_px must be >= 1");
    if (!(camera.viewport_px.x > 0.0f && camera.viewport_px.y > 0.0f)) fail("camera viewport must be > 0 pixels");
    if (!(camera.viewport_px.x / std::max(params.cell_px, 1.0f) <= 8192.0f &&
          camera.viewport_px.y / std::max(params.cell_px, 1.0f) <= 8192.0f))
        fail("grid would exceed 8192 cells per side: raise cell_px");
    if (!(params.body_cell_px >= 1.0f)) fail("body_cell_px must be >= 1");
    if (!(camera.viewport_px.x / std::max(params.body_cell_px, 1.0f) <= 8192.0f &&
          camera.viewport_px.y / std::max(params.body_cell_px, 1.0f) <= 8192.0f))
        fail("the estimate's grid would exceed 8192 cells per side: raise body_cell_px");
    if (!(camera.near_plane > 0.0f)) fail("camera needs near > 0");
    if (!(params.torso_y0 < params.torso_y1 && params.neck_y0 < params.neck_y1 && params.head_y0 < params.head_y1 &&
          params.torso_radius >= 0.0f && params.neck_radius >= 0.0f && params.head_radius >= 0.0f))
        fail("core shapes need y0 < y1 and radius >= 0");
    for (const OcclusionParams::BodyShape& b : {params.body_legs, params.body_torso, params.body_head})
        if (!(b.y0 < b.y1 && b.radius >= 0.0f)) fail("body shapes need y0 < y1 and radius >= 0");
    return ok;
}

namespace {

struct Projector {
    glm::mat4 view_proj;
    glm::vec4 depth_row;  // view depth = depth_row . (p, 1)
    glm::vec2 half_viewport;
    float fx = 0.0f;      // pixels per unit of x (divided by depth when perspective)
    float near_plane = 0.0f;
    bool perspective = true;

    // View depth of `p`.
    float depth(const glm::vec3& p) const { return glm::dot(depth_row, glm::vec4(p, 1.0f)); }
    // Pixel position of `p` (in front of the near plane).
    glm::vec2 pixel(const glm::vec3& p) const {
        const glm::vec4 c = view_proj * glm::vec4(p, 1.0f);
        return {(c.x / c.w + 1.0f) * half_viewport.x, (1.0f - c.y / c.w) * half_viewport.y};
    }
};

// A vertical cylinder's screen rectangles (half width at its middle depth) and that depth. Its axis leans on
// screen away from the view's centre line when the camera is pitched, the more the nearer it is: the inner
// rectangle [ix0, ix1] holds only what the shape covers at every height (empty when the lean is more than
// its width), the outer one [x0, x1] everything it can cover.
struct ShapeRect {
    float x0 = 0, x1 = 0, y0 = 0, y1 = 0, depth = 0;
    float ix0 = 0, ix1 = 0;
    bool in_front = false;  ///< the whole shape beyond the near plane (else the rest is unset)
};

Projector make_projector(const LodCamera& camera) {
    Projector pr;
    pr.view_proj = camera.projection * camera.view;
    pr.depth_row = -glm::vec4(camera.view[0][2], camera.view[1][2], camera.view[2][2], camera.view[3][2]);
    pr.half_viewport = camera.viewport_px * 0.5f;
    pr.fx = camera.projection[0][0] * pr.half_viewport.x;
    pr.near_plane = camera.near_plane;
    pr.perspective = camera.projection[2][3] != 0.0f;
    return pr;
}

// A character's vertical axis in clip space and view depth: the point y metres above the feet is
// feet + y * up (both linear in y), so each shape's ends cost a few multiply-adds and a divide.
struct AxisProjection {
    glm::vec4 feet_clip, up_clip;  // clip position of the feet; clip change per unit height fraction
    float feet_z = 0, up_z = 0;    // view depth of the feet; depth change per unit height fraction
};

AxisProjection project_axis(const Projector& pr, const glm::vec3& feet, float h) {
    return {pr.view_proj * glm::vec4(feet, 1.0f), pr.view_proj[1] * h, pr.depth(feet), pr.depth_row.y * h};
}

ShapeRect project_shape(const Projector& pr, const AxisProjection& ax, float h, float y0, float y1, float radius) {
    ShapeRect r;
    const float zb = ax.feet_z + ax.up_z * y0, zt = ax.feet_z + ax.up_z * y1;
    // Wholly beyond the near plane: a body the near plane cuts is drawn with a hole where it is cut.
    if (!(std::min(zb, zt) - radius * h > pr.near_plane)) return r;
    r.in_front = true;
    r.depth = 0.5f * (zb + zt);
    const float half_w = radius * h * pr.fx / (pr.perspective ? r.depth : 1.0f);
    const glm::vec4 cb = ax.feet_clip + ax.up_clip * y0, ct = ax.feet_clip + ax.up_clip * y1;
    const float xb = (cb.x / cb.w + 1.0f) * pr.half_viewport.x, xt = (ct.x / ct.w + 1.0f) * pr.half_viewport.x;
    const float yb = (1.0f - cb.y / cb.w) * pr.half_viewport.y, yt = (1.0f - ct.y / ct.w) * pr.half_viewport.y;
    r.x0 = std::min(xb, xt) - half_w, r.x1 = std::max(xb, xt) + half_w;
    r.ix0 = std::max(xb, xt) - half_w, r.ix1 = std::min(xb, xt) + half_w;
    r.y0 = std::min(yb, yt), r.y1 = std::max(yb, yt);
    return r;
}

// The screen-horizontal segment through an axis point stays inside a vertical cylinder only when the
// camera's right vector is horizontal (no roll); otherwise no core is used and nothing is occluded.
bool level_camera_of(const LodCamera& camera) { return std::fabs(camera.view[1][0]) < 1e-3f; }

}  // namespace

size_t OcclusionJob::Run() const {
    if (NoneCanBeHidden()) {
        ClearAll();
        return 0;
    }
    Rasterise();
    return Test(0, transforms.size());
}

bool OcclusionJob::NoneCanBeHidden() const {
    size_t visible = 0;
    for (const LodAttributes& a : attributes)
        if (a.visible && ++visible > 1) return false;
    return true;
}

void OcclusionJob::ClearAll() const {
    for (LodAttributes& a : attributes) a.occluded = 0.0f;
}

void OcclusionJob::Rasterise() const {
    PrepareParts(1);
    RasterisePart(0, 1);
    MergeParts(1);
}

void OcclusionJob::PrepareParts(size_t parts) const {
    OcclusionGrid& g = *grid;
    g.resize(camera.viewport_px, params.cell_px, params.body_cell_px);
    constexpr float kFar = std::numeric_limits<float>::infinity();
    std::fill(g.depth.begin(), g.depth.end(), kFar);
    std::fill(g.body.begin(), g.body.end(), kFar);
    g.part_depth.assign(g.depth.size() * (std::max<size_t>(parts, 1) - 1), kFar);
    g.part_body.assign(g.body.size() * (std::max<size_t>(parts, 1) - 1), kFar);
}

void OcclusionJob::MergeParts(size_t parts) const {
    OcclusionGrid& g = *grid;
    const size_t cells = g.depth.size();
    for (size_t p = 1; p < parts; ++p) {
        const float* part = g.part_depth.data() + (p - 1) * cells;
        for (size_t i = 0; i < cells; ++i) g.depth[i] = std::min(g.depth[i], part[i]);
        const float* part_body = g.part_body.data() + (p - 1) * g.body.size();
        for (size_t i = 0; i < g.body.size(); ++i) g.body[i] = std::min(g.body[i], part_body[i]);
    }
    // The block summary of pass 2: nearest and farthest depth of each block (edge blocks partial).
    constexpr int B = kOcclusionBlock;
    g.block_width = (g.width + B - 1) / B;
    g.block_height = (g.height + B - 1) / B;
    const size_t blocks = static_cast<size_t>(g.block_width) * static_cast<size_t>(g.block_height);
    g.block_nearest.assign(blocks, std::numeric_limits<float>::infinity());
    g.block_farthest.assign(blocks, -std::numeric_limits<float>::infinity());
    for (int y = 0; y < g.height; ++y) {
        const float* row = g.depth.data() + static_cast<size_t>(y) * static_cast<size_t>(g.width);
        float* nearest = g.block_nearest.data() + static_cast<size_t>(y / B) * static_cast<size_t>(g.block_width);
        float* farthest = g.block_farthest.data() + static_cast<size_t>(y / B) * static_cast<size_t>(g.block_width);
        for (int bx = 0; bx < g.block_width; ++bx) {
            const int x0 = bx * B, x1 = std::min(g.width, x0 + B);
            float lo = nearest[bx], hi = farthest[bx];
            for (int x = x0; x < x1; ++x) lo = std::min(lo, row[x]), hi = std::max(hi, row[x]);
            nearest[bx] = lo, farthest[bx] = hi;
        }
    }
    // The estimate's grid: nearest depth per block, for its quick "nothing nearer".
    g.body_block_width = (g.body_width + B - 1) / B;
    g.body_block_height = (g.body_height + B - 1) / B;
    g.body_block_nearest.assign(static_cast<size_t>(g.body_block_width) * static_cast<size_t>(g.body_block_height),
                                std::numeric_limits<float>::infinity());
    for (int y = 0; y < g.body_height; ++y) {
        const float* row = g.body.data() + static_cast<size_t>(y) * static_cast<size_t>(g.body_width);
        float* nearest = g.body_block_nearest.data() + static_cast<size_t>(y / B) * static_cast<size_t>(g.body_block_width);
        for (int x = 0; x < g.body_width; ++x) nearest[x / B] = std::min(nearest[x / B], row[x]);
    }
}

void OcclusionJob::RasterisePart(size_t part, size_t parts) const {
    OcclusionGrid& g = *grid;
    float* depth = part == 0 ? g.depth.data() : g.part_depth.data() + (part - 1) * g.depth.size();
    float* body = part == 0 ? g.body.data() : g.part_body.data() + (part - 1) * g.body.size();
    const float cell = params.cell_px, body_cell = params.body_cell_px;
    const Projector pr = make_projector(camera);
    const bool level_camera = level_camera_of(camera);
    const Bounds default_bounds{};

    // Pass 1: cores of every visible character, inner rectangles, whole cells only.
    auto rasterise_core = [&](const glm::vec3& base, float h, float y0, float y1, float radius) {
        const glm::vec3 bottom = base + glm::vec3(0.0f, y0 * h, 0.0f), top = base + glm::vec3(0.0f, y1 * h, 0.0f);
        const float zb = pr.depth(bottom), zt = pr.depth(top);
        // Wholly beyond the near plane: a body the near plane cuts is drawn with a hole where it is cut.
        if (!(std::min(zb, zt) - radius * h > pr.near_plane)) return;
        const float far_z = std::max(zb, zt);
        const float half_w = radius * h * pr.fx / (pr.perspective ? far_z : 1.0f);
        // The inner rectangle is at most 2 half_w wide, and holds a whole cell only when at least a cell
        // wide: a narrower core (every far character's) covers no cell, so it is not projected at all
        // (1% short of a cell, far beyond the pixel coordinates' rounding, so no cell is ever lost).
        if (2.0f * half_w < 0.99f * cell) return;
        const glm::vec2 pb = pr.pixel(bottom), pt = pr.pixel(top);
        const float x0 = std::max(pb.x, pt.x) - half_w, x1 = std::min(pb.x, pt.x) + half_w;
        const float y_lo = std::min(pb.y, pt.y), y_hi = std::max(pb.y, pt.y);
        const int cx0 = std::max(0, static_cast<int>(std::ceil(x0 / cell)));
        const int cx1 = std::min(g.width, static_cast<int>(std::floor(x1 / cell)));
        const int cy0 = std::max(0, static_cast<int>(std::ceil(y_lo / cell)));
        const int cy1 = std::min(g.height, static_cast<int>(std::floor(y_hi / cell)));
        const float core_depth = far_z + radius * h;
        for (int y = cy0; y < cy1; ++y) {
            float* row = depth + static_cast<size_t>(y) * static_cast<size_t>(g.width);
            for (int x = cx0; x < cx1; ++x) row[x] = std::min(row[x], core_depth);
        }
    };
    // The estimate's body shapes: at their axis depth, every cell whose centre their inner rectangle holds.
    auto rasterise_body = [&](const AxisProjection& ax, float h, const OcclusionParams::BodyShape& shape) {
        const ShapeRect r = project_shape(pr, ax, h, shape.y0, shape.y1, shape.radius);
        if (!r.in_front || r.ix1 - r.ix0 < body_cell) return;  // narrower than a cell: a far character's
        const int cx0 = std::max(0, static_cast<int>(std::ceil(r.ix0 / body_cell - 0.5f)));
        const int cx1 = std::min(g.body_width, static_cast<int>(std::floor(r.ix1 / body_cell - 0.5f)) + 1);
        const int cy0 = std::max(0, static_cast<int>(std::ceil(r.y0 / body_cell - 0.5f)));
        const int cy1 = std::min(g.body_height, static_cast<int>(std::floor(r.y1 / body_cell - 0.5f)) + 1);
        for (int y = cy0; y < cy1; ++y) {
            float* row = body + static_cast<size_t>(y) * static_cast<size_t>(g.body_width);
            for (int x = cx0; x < cx1; ++x) row[x] = std::min(row[x], r.depth);
        }
    };
    const size_t n = transforms.size(), share = (n + parts - 1) / std::max<size_t>(parts, 1);
    const size_t begin = std::min(n, part * share), end = std::min(n, begin + share);
    for (size_t i = begin; level_camera && i < end; ++i) {
        if (!attributes[i].visible) continue;
        const Transform& t = transforms[i];
        const float h = (bounds.empty() ? default_bounds : bounds[i]).height * t.scale;
        rasterise_core(t.position, h, params.torso_y0, params.torso_y1, params.torso_radius);
        rasterise_core(t.position, h, params.neck_y0, params.neck_y1, params.neck_radius);
        rasterise_core(t.position, h, params.head_y0, params.head_y1, params.head_radius);
        const AxisProjection ax = project_axis(pr, t.position, h);
        rasterise_body(ax, h, params.body_legs);
        rasterise_body(ax, h, params.body_torso);
        rasterise_body(ax, h, params.body_head);
    }
}

namespace {

constexpr float kMinEstimateCells = 4.0f;  // the estimate's smallest character, in cells of its grid (16 px)

// The estimate for a character standing at `feet`, `h` tall (after MergeParts): the share of the cells of
// its body shapes that nearer body shapes cover, in [0, 1].
float estimate_covered(const OcclusionJob& job, const Projector& pr, const glm::vec3& feet, float h) {
    const OcclusionGrid& g = *job.grid;
    const OcclusionParams& params = job.params;
    const float cell = params.body_cell_px;
    const OcclusionParams::BodyShape* shapes[3] = {&params.body_legs, &params.body_torso, &params.body_head};
    const AxisProjection ax = project_axis(pr, feet, h);
    // Under kMinEstimateCells cells tall its shapes are a cell or two wide: the estimate would be the
    // cells' rounding, not what covers it. 0 (as for a character nothing covers).
    {
        const glm::vec4 top = ax.feet_clip + ax.up_clip;
        if (!(ax.feet_clip.w > 0.0f) || !(top.w > 0.0f)) return 0.0f;  // behind the eye (the shapes say more below)
        const float tall_px = std::fabs(top.y / top.w - ax.feet_clip.y / ax.feet_clip.w) * pr.half_viewport.y;
        if (tall_px < kMinEstimateCells * cell) return 0.0f;
    }
    // Nearer than its own nearest shape by its torso's radius: its own shapes never count.
    float front = std::numeric_limits<float>::infinity();
    for (const OcclusionParams::BodyShape* b : shapes) front = std::min(front, ax.feet_z + ax.up_z * 0.5f * (b->y0 + b->y1));
    front -= params.body_torso.radius * h;
    int cx0 = g.body_width, cx1 = 0, cy0 = g.body_height, cy1 = 0;  // the cells of all three (outer rectangles)
    int box[3][4];
    for (int k = 0; k < 3; ++k) {
        const ShapeRect r = project_shape(pr, ax, h, shapes[k]->y0, shapes[k]->y1, shapes[k]->radius);
        if (!r.in_front) return 0.0f;
        box[k][0] = std::max(0, static_cast<int>(std::floor(r.x0 / cell)));
        box[k][1] = std::min(g.body_width, static_cast<int>(std::ceil(r.x1 / cell)));
        box[k][2] = std::max(0, static_cast<int>(std::floor(r.y0 / cell)));
        box[k][3] = std::min(g.body_height, static_cast<int>(std::ceil(r.y1 / cell)));
        cx0 = std::min(cx0, box[k][0]), cx1 = std::max(cx1, box[k][1]);
        cy0 = std::min(cy0, box[k][2]), cy1 = std::max(cy1, box[k][3]);
    }
    if (cx0 >= cx1 || cy0 >= cy1) return 0.0f;
    constexpr int B = kOcclusionBlock;
    float nearest = std::numeric_limits<float>::infinity();
    for (int by = cy0 / B; by <= (cy1 - 1) / B; ++by)
        for (int bx = cx0 / B; bx <= (cx1 - 1) / B; ++bx)
            nearest = std::min(nearest, g.body_block_nearest[static_cast<size_t>(by) * static_cast<size_t>(g.body_block_width) + static_cast<size_t>(bx)]);
    if (!(nearest < front)) return 0.0f;
    constexpr double kSamples = 16.0;  // per shape
    size_t covered = 0, seen = 0;
    for (const auto& b : box) {
        if (b[0] >= b[1] || b[2] >= b[3]) continue;
        const double cells = double(b[1] - b[0]) * double(b[3] - b[2]);
        const int step = cells <= kSamples ? 1 : static_cast<int>(std::ceil(std::sqrt(cells / kSamples)));
        for (int y = b[2]; y < b[3]; y += step) {
            const float* row = g.body.data() + static_cast<size_t>(y) * static_cast<size_t>(g.body_width);
            for (int x = b[0]; x < b[1]; x += step) covered += row[x] < front ? 1u : 0u, ++seen;
        }
    }
    return seen == 0 ? 0.0f : static_cast<float>(covered) / static_cast<float>(seen);
}

}  // namespace

size_t OcclusionJob::Test(size_t begin, size_t end) const {
    const OcclusionGrid& g = *grid;
    const float cell = params.cell_px;
    constexpr float kFar = std::numeric_limits<float>::infinity();
    const Projector pr = make_projector(camera);
    const bool level_camera = level_camera_of(camera);
    const Bounds default_bounds{};
    assert(g.block_nearest.size() == static_cast<size_t>(g.block_width) * static_cast<size_t>(g.block_height) &&
           g.block_width * kOcclusionBlock >= g.width && g.block_height * kOcclusionBlock >= g.height);  // MergeParts ran
    // Pass 2: bounds boxes, outer rectangles, every cell touched.
    size_t full = 0;
    for (size_t i = begin; i < end && i < transforms.size(); ++i) {
        LodAttributes& a = attributes[i];
        a.occluded = 0.0f;
        if (!a.visible || !level_camera) continue;
        const Transform& t = transforms[i];
        const Bounds& b = bounds.empty() ? default_bounds : bounds[i];
        const float h = b.height * t.scale, r = b.radius * t.scale;
        // The bounds box's eight corners (+-r, 0 or h, +-r) from the feet. Clip position and depth are linear in
        // the point, so each corner is the feet's plus signed multiples of three matrix columns (one product, not
        // eight), and the nearest depth is the feet's minus what the offsets can take off.
        const glm::vec4 feet = pr.view_proj * glm::vec4(t.position, 1.0f);
        const float feet_z = pr.depth(t.position);
        const float near_z = feet_z - std::fabs(pr.depth_row.x * r) - std::fabs(pr.depth_row.z * r) + std::min(pr.depth_row.y * h, 0.0f);
        if (!(near_z > pr.near_plane)) continue;  // a corner at or behind the near plane
        const glm::vec4 ex = pr.view_proj[0] * r, ey = pr.view_proj[1] * h, ez = pr.view_proj[2] * r;
        float qx_lo = kFar, qx_hi = -kFar, qy_lo = kFar, qy_hi = -kFar;  // extremes of x/w and y/w
        for (int k = 0; k < 4; ++k) {
            const float sx = k & 1 ? 1.0f : -1.0f, sz = k & 2 ? 1.0f : -1.0f;
            const float x = feet.x + sx * ex.x + sz * ez.x, y = feet.y + sx * ex.y + sz * ez.y, w = feet.w + sx * ex.w + sz * ez.w;
            const float inv0 = 1.0f / w, inv1 = 1.0f / (w + ey.w);
            const float x0 = x * inv0, x1 = (x + ey.x) * inv1, y0 = y * inv0, y1 = (y + ey.y) * inv1;
            qx_lo = std::min(qx_lo, std::min(x0, x1)), qx_hi = std::max(qx_hi, std::max(x0, x1));
            qy_lo = std::min(qy_lo, std::min(y0, y1)), qy_hi = std::max(qy_hi, std::max(y0, y1));
        }
        glm::vec2 lo((qx_lo + 1.0f) * pr.half_viewport.x, (1.0f - qy_hi) * pr.half_viewport.y);
        glm::vec2 hi((qx_hi + 1.0f) * pr.half_viewport.x, (1.0f - qy_lo) * pr.half_viewport.y);
        if (geom.empty() || geom[i].method != GeomMethod::Hidden) lo -= params.enter_margin_px, hi += params.enter_margin_px;
        const int cx0 = std::max(0, static_cast<int>(std::floor(lo.x / cell)));
        const int cx1 = std::min(g.width, static_cast<int>(std::ceil(hi.x / cell)));
        const int cy0 = std::max(0, static_cast<int>(std::floor(lo.y / cell)));
        const int cy1 = std::min(g.height, static_cast<int>(std::ceil(hi.y / cell)));
        if (cx0 >= cx1 || cy0 >= cy1) continue;
        // Fully covered? The blocks under the rectangle answer when none or all of their cells are nearer
        // than the bounds (the answer counting cells would give, without reading them); else every cell is read.
        bool hidden = false;
        {
            constexpr int B = kOcclusionBlock;
            float nearest = kFar, farthest = -kFar;
            for (int by = cy0 / B; by <= (cy1 - 1) / B; ++by) {
                const size_t row = static_cast<size_t>(by) * static_cast<size_t>(g.block_width);
                for (int bx = cx0 / B; bx <= (cx1 - 1) / B; ++bx)
                    nearest = std::min(nearest, g.block_nearest[row + static_cast<size_t>(bx)]),
                    farthest = std::max(farthest, g.block_farthest[row + static_cast<size_t>(bx)]);
            }
            hidden = farthest < near_z;
            if (!hidden && nearest < near_z) {
                hidden = true;
                for (int y = cy0; hidden && y < cy1; ++y) {
                    const float* row = g.depth.data() + static_cast<size_t>(y) * static_cast<size_t>(g.width);
                    for (int x = cx0; x < cx1; ++x)
                        if (!(row[x] < near_z)) {
                            hidden = false;
                            break;
                        }
                }
            }
        }
        if (hidden) {
            a.occluded = 1.0f;
            ++full;
        } else {
            a.occluded = std::min(estimate_covered(*this, pr, t.position, h), 0.99f);
        }
    }
    return full;
}

}  // namespace aloha
