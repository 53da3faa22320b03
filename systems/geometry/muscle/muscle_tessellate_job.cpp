#include "systems/geometry/muscle/muscle_tessellate_job.hpp"

#include <cmath>

namespace aloha {

bool MuscleTessellateJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& what) {
        ok = false;
        if (errors) errors->push_back("MuscleTessellateJob: " + what);
    };
    if (tables == nullptr) {
        fail("no tessellation tables");
        return false;
    }
    const size_t muscles = tables->muscle_count();
    if (muscles == 0) fail("tables were built for an empty muscle set");
    else if (centres.size() % muscles != 0)
        fail("centres holds " + std::to_string(centres.size()) + " shapes, not a multiple of " + std::to_string(muscles) +
             " muscles per character");
    if (rotations.size() != centres.size()) fail("rotations and centres differ in length");
    if (radii.size() != centres.size()) fail("radii and centres differ in length");
    const size_t need = centres.size() * tables->vertices_per_muscle();
    if (positions.size() < need) fail("positions holds " + std::to_string(positions.size()) + ", needs " + std::to_string(need));
    if (normals.size() < need) fail("normals holds " + std::to_string(normals.size()) + ", needs " + std::to_string(need));
    for (size_t s = 0; s < radii.size(); ++s) {
        if (!(radii[s].x > 0.0f && radii[s].y > 0.0f && radii[s].z > 0.0f)) {
            fail("shape " + std::to_string(s) + " has a non-positive radius");
            break;
        }
    }
    return ok;
}

void MuscleTessellateJob::Run() const {
    const uint32_t T = tables->theta_steps(), P = tables->phi_steps();
    const size_t per = tables->vertices_per_muscle();
    const size_t muscles = tables->muscle_count();
    glm::vec3* pos = positions.data();
    glm::vec3* nrm = normals.data();
    for (size_t s = 0; s < centres.size(); ++s) {
        const SuperEllipsoidTables::View tab = tables->muscle(s % muscles);
        const glm::mat3 R = glm::mat3_cast(rotations[s]);
        const glm::vec3 r = radii[s];
        const glm::vec3 c = centres[s];
        const glm::vec3 ax = R[0] * r.x, ay = R[1] * r.y, az = R[2] * r.z;        // position basis
        const glm::vec3 nx = R[0] / r.x, ny = R[1] / r.y, nz = R[2] / r.z;        // gradient basis
        glm::vec3* p = pos + s * per;
        glm::vec3* n = nrm + s * per;
        p[0] = c - az;  // south pole (phi = -pi/2): (0, 0, -rz)
        n[0] = -R[2];
        p[per - 1] = c + az;
        n[per - 1] = R[2];
        size_t v = 1;
        for (uint32_t ring = 0; ring + 1 < P; ++ring) {
            const float ca = tab.ring_cos[ring], sa = tab.ring_sin[ring];
            const float nca = tab.ring_ncos[ring], nsa = tab.ring_nsin[ring];
            const glm::vec3 pbase = c + az * sa, pu = ax * ca, pv = ay * ca;
            const glm::vec3 nbase = nz * nsa, nu = nx * nca, nv = ny * nca;
            for (uint32_t t = 0; t < T; ++t, ++v) {
                p[v] = pbase + pu * tab.col_cos[t] + pv * tab.col_sin[t];
                const glm::vec3 g = nbase + nu * tab.col_ncos[t] + nv * tab.col_nsin[t];
                n[v] = g * (1.0f / std::sqrt(glm::dot(g, g)));
            }
        }
    }
}

}  // namespace aloha
