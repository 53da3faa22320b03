// The pose pool: local poses and model matrices of many characters of one skeleton, stored
// slot-major structure-of-arrays (all translations, all rotations, all scales, all matrices), and
// the batched sample + local-to-model job that fills it in one tight loop.
#pragma once

#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/sampling.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Owns `slot_count` poses of `joint_count` joints each. Slot s's joints are contiguous.
class PosePool {
public:
    PosePool() = default;
    /// Allocates `slot_count` poses of `joint_count` joints, all set to `rest` when given (else identity).
    PosePool(int joint_count, size_t slot_count, const Skeleton* rest = nullptr);

    /// Joints per pose.
    [[nodiscard]] int joint_count() const { return joints_; }
    /// Number of slots.
    [[nodiscard]] size_t slot_count() const { return slots_; }
    /// Mutable view of slot `s` (requires s < slot_count()).
    [[nodiscard]] PoseView view(size_t s);
    /// Read-only view of slot `s` (requires s < slot_count()).
    [[nodiscard]] ConstPoseView view(size_t s) const;
    /// Copies the skeleton's rest pose into slot `s` (local and model). Requires a matching skeleton.
    void set_rest(size_t s, const Skeleton& skeleton);
    /// Writes `clip`'s first pose into slot `s` (local and model) with the root joint at its rest horizontal place (the
    /// clip's horizontal offset is no placement): the stance a character of `skeleton` holds until posed, and the
    /// impostors' standing row. Requires `clip` built on `skeleton`.
    void set_stance(size_t s, const AnimationClip& clip, const Skeleton& skeleton);

private:
    int joints_ = 0;
    size_t slots_ = 0;
    std::vector<glm::vec3> t_;
    std::vector<glm::quat> r_;
    std::vector<glm::vec3> s_;
    std::vector<glm::mat4> m_;
};

/// Samples one clip for many characters and converts each pose to model space, in one loop.
/// Character i plays `clip` at `times[i]` into pool slot `slots[i]` using `caches[i]`.
struct AnimateBatchJob {
    const AnimationClip* clip = nullptr;        ///< required; built for `skeleton`
    const Skeleton* skeleton = nullptr;         ///< required
    bool loop = true;                           ///< wrap (true) or clamp (false) times
    std::span<const float> times;               ///< playback time per character (seconds)
    std::span<const uint32_t> slots;            ///< pool slot per character, times.size() elements
    std::span<SamplingCache> caches;            ///< per-character cursors, times.size() elements
    PosePool* pool = nullptr;                   ///< output poses (required)

    /// True when the job can run; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Samples and converts every character. Requires Validate().
    void Run() const;
};

}  // namespace aloha
