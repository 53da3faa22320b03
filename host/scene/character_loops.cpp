// Looped versions of a type's clips (character_loops.hpp).
#include "host/scene/character_loops.hpp"

#include "systems/motion/clip.hpp"
#include "systems/motion/library/loop_cut.hpp"
#include "systems/motion/library/loop_seam.hpp"

#include <cstdio>

namespace aloha {

namespace {

// A held pose: one key, or a few within a tenth of a second.
constexpr float kHeldPoseSeconds = 0.1f;

// What a seam measured: whether it is within the loop bars, and its figures as the notes give them.
struct SeamVerdict {
    bool closable = false;
    std::string figures;  // "its ends differ by ... " (with the limits when it is not closable)
};

SeamVerdict judge(const LoopCut& s) {
    SeamVerdict v;
    const float bend = seam_bend(s.pose_error, s.velocity_error);
    v.closable = bend <= kMaxSeamBend;
    char buf[200];
    const int n = std::snprintf(buf, sizeof buf, "its ends differ by %.1f cm per joint and %.2f m/s", static_cast<double>(100.0f * s.pose_error),
                                static_cast<double>(s.velocity_error));
    if (!v.closable && n > 0 && static_cast<size_t>(n) < sizeof buf)
        std::snprintf(buf + n, sizeof buf - static_cast<size_t>(n), ", too far to close (closing would bend it %.1f cm per joint, limit %.1f cm)",
                      static_cast<double>(100.0f * bend), static_cast<double>(100.0f * kMaxSeamBend));
    v.figures = buf;
    return v;
}

// The looped version of clip `id` built from `take` when its ends nearly meet; the verdict either way, or the
// message why the seam could not be measured.
Result<SeamVerdict> loop_version(CharacterType& type, ClipId id, const RawAnimation& take, const std::string& file) {
    Result<LoopCut> seam = whole_take_seam(take, type.skeleton, file);
    if (!seam.ok()) return seam.error();
    SeamVerdict v = judge(seam.value());
    if (!v.closable) return v;
    RawAnimation closed = take;
    close_loop_seam(closed);
    Result<AnimationClip> built = build_clip(closed, type.skeleton);
    if (!built.ok()) return built.error();  // the same tracks built before, values moved a little: cannot fail
    type.clips.set_looped(id, std::move(built).value());
    return v;
}

}  // namespace

std::string close_clip_seam(CharacterType& type, ClipId id, const RawAnimation& take, const std::string& file) {
    if (take.duration < kHeldPoseSeconds) return "";
    Result<SeamVerdict> v = loop_version(type, id, take, file);
    if (!v.ok()) return " (" + v.error().message + ")";
    return " (" + v.value().figures + (v.value().closable ? ": closed)" : "; faded over the level's cross-fade time each time idlers repeat it)");
}

void close_clip_seams(CharacterType& type, std::span<const LoadedTake> takes) {
    std::string closed, jumping;  // jumping: faded at each wrap by the motion controller
    for (const LoadedTake& t : takes) {
        const int id = type.clips.find(t.take.name);
        if (id < 0 || id == type.idle_clip || type.clips.has_looped(static_cast<ClipId>(id)) || t.take.duration < kHeldPoseSeconds) continue;
        Result<SeamVerdict> v = loop_version(type, static_cast<ClipId>(id), t.take, t.file);
        if (!v.ok()) continue;  // too short to measure a seam (three steps): a clip that short is no loop to close
        std::string& list = v.value().closable ? closed : jumping;
        list += (list.empty() ? "'" : "; '") + t.take.name + "' (" + v.value().figures + ")";
    }
    if (!closed.empty()) type.notes.push_back("played looping, closed where they repeat: " + closed);
    if (!jumping.empty()) type.notes.push_back("played looping, these are faded where they repeat (over the level's cross-fade time): " + jumping);
}

}  // namespace aloha
