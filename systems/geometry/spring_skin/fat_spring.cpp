// Fat springs: exact damped-oscillator step per frame with strain limiting (see fat_spring.hpp).
#include "systems/geometry/spring_skin/fat_spring.hpp"

#include "systems/geometry/spring_skin/fat_spring_step.hpp"

#include "systems/geometry/surface_grid.hpp"

#include <cmath>
#include <numbers>

namespace aloha {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

}  // namespace

FatSpringPool::FatSpringPool(uint32_t characters, uint32_t muscles_per_character, uint32_t theta_steps,
                             uint32_t phi_steps)
    : characters_(characters), muscles_(muscles_per_character), theta_(theta_steps), phi_(phi_steps) {
    assert(theta_steps >= 3 && phi_steps >= 2);
    const size_t n = static_cast<size_t>(characters) * springs_per_character();
    end_.assign(n, glm::vec3(0.0f));
    velocity_.assign(n, glm::vec3(0.0f));
    prev_rest_.assign(n, glm::vec3(0.0f));
    initialised_.assign(static_cast<size_t>(characters) * muscles_, 0);
}

uint32_t FatSpringPool::springs_per_character() const { return muscles_ * grid_vertex_count(theta_, phi_); }

FatSpringStateView FatSpringPool::view(uint32_t first, uint32_t count) {
    assert(first + count <= characters_);
    const size_t s0 = static_cast<size_t>(first) * springs_per_character();
    const size_t sn = static_cast<size_t>(count) * springs_per_character();
    return {std::span(end_).subspan(s0, sn), std::span(velocity_).subspan(s0, sn),
            std::span(prev_rest_).subspan(s0, sn),
            std::span(initialised_).subspan(static_cast<size_t>(first) * muscles_, static_cast<size_t>(count) * muscles_)};
}

void FatSpringPool::reset(uint32_t c) {
    assert(c < characters_);
    std::fill_n(initialised_.begin() + static_cast<ptrdiff_t>(c) * muscles_, muscles_, uint8_t{0});
}

bool FatSpringJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("FatSpringJob: " + std::move(message));
    };
    if (theta_steps < 3) fail("theta_steps must be >= 3");
    if (phi_steps < 2) fail("phi_steps must be >= 2");
    if (!(std::isfinite(params.dt) && params.dt > 0.0f)) fail("params.dt must be finite and > 0");
    if (!(std::isfinite(params.normal_hz) && params.normal_hz > 0.0f)) fail("params.normal_hz must be > 0");
    if (!(std::isfinite(params.lateral_hz) && params.lateral_hz > 0.0f)) fail("params.lateral_hz must be > 0");
    if (!(std::isfinite(params.normal_damping) && params.normal_damping >= 0.0f)) fail("params.normal_damping must be >= 0");
    if (!(std::isfinite(params.max_strain) && params.max_strain > 0.0f)) fail("params.max_strain must be > 0");
    if (theta_steps >= 3 && phi_steps >= 2) {
        const size_t V = grid_vertex_count(theta_steps, phi_steps);
        const size_t n = muscle_positions.size();
        if (n % V != 0) fail("muscle_positions size is not a multiple of the grid vertex count");
        if (muscle_normals.size() != n) fail("muscle_normals size differs from muscle_positions");
        if (thickness.size() * V != n) fail("thickness needs one value per muscle");
        if (state.end.size() != n || state.velocity.size() != n || state.prev_rest.size() != n)
            fail("state spans must have one entry per spring");
        if (state.initialised.size() != thickness.size()) fail("state.initialised needs one flag per muscle");
    }
    return ok;
}

void FatSpringJob::Run() const {
    assert(Validate());
    const uint32_t V = grid_vertex_count(theta_steps, phi_steps);
    const SpringStepper stepper(params);
    const size_t muscles = thickness.size();
    for (size_t m = 0; m < muscles; ++m) {
        const float h = thickness[m];
        const size_t base = m * V;
        if (state.initialised[m] == kSpringsRestart) {  // start at rest
            for (size_t i = base; i < base + V; ++i) {
                const glm::vec3 rest = muscle_positions[i] + h * muscle_normals[i];
                state.end[i] = rest;
                state.prev_rest[i] = rest;
                state.velocity[i] = glm::vec3(0.0f);
            }
            state.initialised[m] = kSpringsStarted;
            continue;
        }
        const bool adopt = state.initialised[m] == kSpringsStarted;  // moving with the rest ends from this step
        for (size_t i = base; i < base + V; ++i) {
            const glm::vec3 n = muscle_normals[i];
            const glm::vec3 rest = muscle_positions[i] + h * n;
            if (adopt) state.velocity[i] = (rest - state.prev_rest[i]) * stepper.inv_dt;
            stepper.step(rest, n, h, state.end[i], state.velocity[i], state.prev_rest[i]);
        }
        state.initialised[m] = kSpringsRunning;
    }
}


SpringTransition exact_transition(double omega, double zeta, double dt) {
    SpringTransition tr{};
    if (std::abs(zeta - 1.0) < 1e-4) {  // critically damped
        const double ex = std::exp(-omega * dt);
        tr = {static_cast<float>(ex * (1.0 + omega * dt)), static_cast<float>(ex * dt),
              static_cast<float>(-ex * omega * omega * dt), static_cast<float>(ex * (1.0 - omega * dt))};
    } else if (zeta < 1.0) {  // under-damped
        const double wd = omega * std::sqrt(1.0 - zeta * zeta);
        const double ex = std::exp(-zeta * omega * dt), c = std::cos(wd * dt), s = std::sin(wd * dt);
        tr = {static_cast<float>(ex * (c + zeta * omega * s / wd)), static_cast<float>(ex * s / wd),
              static_cast<float>(-ex * omega * omega * s / wd), static_cast<float>(ex * (c - zeta * omega * s / wd))};
    } else {  // over-damped: two real decaying modes
        const double root = std::sqrt(zeta * zeta - 1.0);
        const double r1 = -omega * (zeta - root), r2 = -omega * (zeta + root);
        const double e1 = std::exp(r1 * dt), e2 = std::exp(r2 * dt), inv = 1.0 / (r1 - r2);
        tr = {static_cast<float>((r1 * e2 - r2 * e1) * inv), static_cast<float>((e1 - e2) * inv),
              static_cast<float>(r1 * r2 * (e2 - e1) * inv), static_cast<float>((r1 * e1 - r2 * e2) * inv)};
    }
    return tr;
}

SpringStepper::SpringStepper(const FatSpringParams& params)
    : normal(exact_transition(kTwoPi * params.normal_hz, params.normal_damping, params.dt)),
      lateral(exact_transition(kTwoPi * params.lateral_hz, 1.0, params.dt)),
      inv_dt(1.0f / params.dt),
      normal_omega(kTwoPi * params.normal_hz),
      max_strain(params.max_strain) {}

void SpringStepper::step(glm::vec3 rest, glm::vec3 n, float h, glm::vec3& end, glm::vec3& velocity, glm::vec3& prev_rest) const {
    const float max_dev = max_strain * h, max_rate = max_dev * normal_omega;
    const glm::vec3 w = (rest - prev_rest) * inv_dt;
    const glm::vec3 d0 = end - prev_rest;
    const glm::vec3 u0 = velocity - w;
    const float dn = glm::dot(d0, n), un = glm::dot(u0, n);
    const glm::vec3 dl = d0 - dn * n, ul = u0 - un * n;
    glm::vec3 d1 = (normal.a * dn + normal.b * un) * n + lateral.a * dl + lateral.b * ul;
    glm::vec3 u1 = (normal.c * dn + normal.e * un) * n + lateral.c * dl + lateral.e * ul;
    // Strain limiting: position on the ball |d| <= max_dev, outward relative velocity removed.
    const float dlen2 = glm::dot(d1, d1);
    if (dlen2 > max_dev * max_dev) {
        const glm::vec3 dir = d1 / std::sqrt(dlen2);
        d1 = max_dev * dir;
        const float outward = glm::dot(u1, dir);
        if (outward > 0.0f) u1 -= outward * dir;
    }
    const float ulen2 = glm::dot(u1, u1);
    if (ulen2 > max_rate * max_rate) u1 *= max_rate / std::sqrt(ulen2);
    if (!(std::isfinite(d1.x) && std::isfinite(d1.y) && std::isfinite(d1.z) && std::isfinite(u1.x) && std::isfinite(u1.y) &&
          std::isfinite(u1.z))) {  // non-finite input: restart at rest
        d1 = glm::vec3(0.0f);
        u1 = glm::vec3(0.0f);
    }
    end = rest + d1;
    velocity = w + u1;
    prev_rest = rest;
}

float fat_spring_energy(const FatSpringParams& params, glm::vec3 end, glm::vec3 velocity, glm::vec3 rest_end,
                        glm::vec3 rest_velocity, glm::vec3 normal) {
    const float wn = kTwoPi * params.normal_hz, wt = kTwoPi * params.lateral_hz;
    const glm::vec3 d = end - rest_end, u = velocity - rest_velocity;
    const float dn = glm::dot(d, normal);
    const glm::vec3 dl = d - dn * normal;
    return 0.5f * wn * wn * dn * dn + 0.5f * wt * wt * glm::dot(dl, dl) + 0.5f * glm::dot(u, u);
}

}  // namespace aloha
