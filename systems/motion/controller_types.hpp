// Types the motion controller shares with the modules around it: how much of each pose is read this
// frame (PoseUse), and the interface of the methods other modules implement (reach, look-at, dynamic
// walking) that the controller dispatches to (MethodContext, MethodHook, MethodRelease).
#pragma once

#include <cstdint>

#include "components/lod.hpp"
#include "components/motion.hpp"
#include "components/transform.hpp"
#include "engine/anim/pose.hpp"
#include "engine/anim/skeleton.hpp"

namespace aloha {

/// How much of a character's pose the stages after motion read this frame (MotionUpdateJob::pose_use).
/// A pose nobody reads is not written: a character is only ever shown posed as if it had been all along.
enum class PoseUse : uint8_t {
    Unseen = 0,      ///< nothing reads it (e.g. geometry hidden): stateless clip poses are left stale and
                     ///< posed at once, on a fresh key span, when the character is seen again
    AtUpdates = 1,   ///< read on the frames it is posed only (rigid proxies, linear-blend skins): not
                     ///< interpolated between throttled updates, no interpolation keys taken (posed at
                     ///< once, on a fresh key span, when it is read every frame again)
    EveryFrame = 2,  ///< read every frame (layered skins, geomorphs, metrics): interpolated between updates
};

/// Methods that other modules implement and the controller dispatches to.
enum class MethodSlot : uint8_t { Reach = 0, LookAt = 1, DynamicWalk = 2, Count = 3 };

/// What a method hook sees for one character. `pose` holds the base local pose and its model
/// matrices (up to date); the hook edits the local pose (and may edit transform/velocity). The
/// controller runs local-to-model again after the hook.
struct MethodContext {
    uint32_t character = 0;
    const MotionRequest* request = nullptr;  ///< the request being executed
    const Skeleton* skeleton = nullptr;
    const AnimLod* lod = nullptr;            ///< IK solver / iterations / tolerance chosen by the resolver
    PoseView pose;
    Transform* transform = nullptr;
    Velocity* velocity = nullptr;
    float dt = 0.0f;                         ///< seconds since this character was last posed
    float request_time = 0.0f;               ///< seconds since the request started
    bool first = false;                      ///< first evaluation of this request (it started this frame)
    bool layered = false;                    ///< an overlay (set_overlay) over the pose of the request beneath
    bool base_is_live = true;                ///< layered: the pose beneath was produced this call (false at rest: it is the pose shown)
    float layer_weight = 1.0f;               ///< layered: weight of the overlay's result over the pose beneath, in [0, 1]
};

/// A method implementation: `user` is the pointer given at registration. Must not allocate per call.
/// update_parallel calls it concurrently for different characters: it may touch only state that
/// belongs to ctx.character (and must not grow shared containers).
using MethodHook = void (*)(void* user, MethodContext& ctx);

/// Called (serially, from the bookkeeping phase) when `character` stops using a method: its
/// request ended or changed kind, or its walk left the method. Frees per-character method state.
using MethodRelease = void (*)(void* user, uint32_t character);

namespace motion_detail {
/// What of an AnimLod shapes the pose (level, walk method, IK solver and iterations, update interval),
/// packed into one comparable value.
inline int64_t anim_signature(const AnimLod& l) {
    return static_cast<int64_t>(l.level) | static_cast<int64_t>(l.walk) << 8 | static_cast<int64_t>(l.ik) << 16 |
           static_cast<int64_t>(l.ik_iterations) << 24 | static_cast<int64_t>(l.update_interval) << 32;
}
}  // namespace motion_detail

}  // namespace aloha
