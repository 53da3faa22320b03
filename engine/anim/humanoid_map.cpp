#include "engine/anim/humanoid_map.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <optional>

namespace aloha {

namespace {

// Canonical joints, parents first; each sided joint's right twin directly follows the left one.
constexpr std::array<CanonicalJoint, 31> kCanonical = {{
    {"Hips", -1, true, -1},
    {"LHipJoint", 0, false, 0},     {"RHipJoint", 0, false, 1},
    {"LeftHip", 1, true, 0},        {"RightHip", 2, true, 1},
    {"LeftKnee", 3, true, 0},       {"RightKnee", 4, true, 1},
    {"LeftAnkle", 5, true, 0},      {"RightAnkle", 6, true, 1},
    {"LeftToe", 7, false, 0},       {"RightToe", 8, false, 1},
    {"lowerback", 0, false, -1},
    {"Chest", 11, false, -1},
    {"Chest2", 12, false, -1},
    {"lowerneck", 13, false, -1},
    {"Neck", 14, false, -1},
    {"Head", 15, true, -1},
    {"LeftCollar", 13, false, 0},   {"RightCollar", 13, false, 1},
    {"LeftShoulder", 17, true, 0},  {"RightShoulder", 18, true, 1},
    {"LeftElbow", 19, true, 0},     {"RightElbow", 20, true, 1},
    {"LeftWrist", 21, true, 0},     {"RightWrist", 22, true, 1},
    {"lhand", 23, false, 0},        {"rhand", 24, false, 1},
    {"LFingers", 25, false, 0},     {"RFingers", 26, false, 1},
    {"LThumb", 23, false, 0},       {"RThumb", 24, false, 1},
}};

// One row of a convention: the canonical joint (the left one for sided joints) and the keys
// (joint_name_key without the side) tried in order of preference.
struct Row {
    const char* canonical;
    std::vector<std::string> keys;
};

struct Convention {
    const char* name;
    std::vector<Row> rows;
};

// Unity Humanoid bone names (VRM's humanoid bones are the same names in camelCase).
std::vector<Row> unity_rows(const std::string& sided_prefix, const std::string& centre_prefix) {
    auto c = [&](const char* k) { return centre_prefix + k; };
    auto s = [&](const char* k) { return sided_prefix + k; };
    return {{"Hips", {c("hips")}},          {"LeftHip", {s("upperleg")}},      {"LeftKnee", {s("lowerleg")}},
            {"LeftAnkle", {s("foot")}},     {"LeftToe", {s("toes"), s("toebase")}},
            {"lowerback", {c("spine")}},    {"Chest", {c("chest")}},          {"Chest2", {c("upperchest")}},
            {"lowerneck", {c("neck")}},     {"Head", {c("head")}},            {"LeftCollar", {s("shoulder")}},
            {"LeftShoulder", {s("upperarm")}}, {"LeftElbow", {s("lowerarm")}}, {"LeftWrist", {s("hand")}},
            {"LFingers", {s("middleproximal"), s("middle1")}}, {"LThumb", {s("thumbproximal"), s("thumb1")}}};
}

const std::vector<Convention>& conventions() {
    static const std::vector<Convention> table = {
        {"CMU BVH",
         {{"Hips", {"hips"}}, {"LHipJoint", {"hipjoint"}}, {"LeftHip", {"hip"}}, {"LeftKnee", {"knee"}},
          {"LeftAnkle", {"ankle"}}, {"LeftToe", {"toe"}}, {"lowerback", {"lowerback"}}, {"Chest", {"chest", "upperback"}},
          {"Chest2", {"chest2", "thorax"}}, {"lowerneck", {"lowerneck"}}, {"Neck", {"neck", "upperneck"}},
          {"Head", {"head"}}, {"LeftCollar", {"collar"}}, {"LeftShoulder", {"shoulder"}}, {"LeftElbow", {"elbow"}},
          {"LeftWrist", {"wrist"}}, {"lhand", {"hand"}}, {"LFingers", {"fingers"}}, {"LThumb", {"thumb"}}}},
        {"Mixamo / HumanIK",
         {{"Hips", {"hips"}}, {"LHipJoint", {"hipjoint"}}, {"LeftHip", {"upleg"}}, {"LeftKnee", {"leg"}},
          {"LeftAnkle", {"foot"}}, {"LeftToe", {"toebase"}}, {"lowerback", {"spine", "lowerback"}},
          {"Chest", {"spine1"}}, {"Chest2", {"spine2"}}, {"lowerneck", {"neck"}}, {"Neck", {"neck1"}},
          {"Head", {"head"}}, {"LeftCollar", {"shoulder"}}, {"LeftShoulder", {"arm"}}, {"LeftElbow", {"forearm"}},
          {"LeftWrist", {"hand"}}, {"LFingers", {"handmiddle1", "fingerbase"}}, {"LThumb", {"handthumb1"}}}},
        {"Unity Humanoid / VRM", unity_rows("", "")},
        {"VRoid", unity_rows("jbip", "jbipc")},
        {"Unreal mannequin",
         {{"Hips", {"pelvis"}}, {"LeftHip", {"thigh"}}, {"LeftKnee", {"calf"}}, {"LeftAnkle", {"foot"}},
          {"LeftToe", {"ball"}}, {"lowerback", {"spine01"}}, {"Chest", {"spine02"}},
          {"Chest2", {"spine05", "spine04", "spine03"}}, {"lowerneck", {"neck01"}}, {"Neck", {"neck02"}},
          {"Head", {"head"}}, {"LeftCollar", {"clavicle"}}, {"LeftShoulder", {"upperarm"}},
          {"LeftElbow", {"lowerarm"}}, {"LeftWrist", {"hand"}}, {"LFingers", {"middle01"}}, {"LThumb", {"thumb01"}}}},
        {"Poser / DAZ",
         {{"Hips", {"hip"}}, {"LeftHip", {"thigh", "thighbend"}}, {"LeftKnee", {"shin"}}, {"LeftAnkle", {"foot"}},
          {"LeftToe", {"toe", "toes"}}, {"lowerback", {"abdomen", "abdomenlower"}},
          {"Chest", {"abdomen2", "abdomenupper"}}, {"Chest2", {"chest", "chestupper"}},
          {"lowerneck", {"neck", "necklower"}}, {"Neck", {"neckupper"}}, {"Head", {"head"}},
          {"LeftCollar", {"collar"}}, {"LeftShoulder", {"shldr", "shldrbend"}},
          {"LeftElbow", {"forearm", "forearmbend"}}, {"LeftWrist", {"hand"}}, {"LFingers", {"mid1"}},
          {"LThumb", {"thumb1"}}}},
        {"Blender Rigify",
         {{"Hips", {"spine"}}, {"LeftHip", {"thigh"}}, {"LeftKnee", {"shin"}}, {"LeftAnkle", {"foot"}},
          {"LeftToe", {"toe"}}, {"lowerback", {"spine001"}}, {"Chest", {"spine002"}}, {"Chest2", {"spine003"}},
          {"lowerneck", {"spine004"}}, {"Neck", {"spine005"}}, {"Head", {"spine006"}},
          {"LeftCollar", {"shoulder"}}, {"LeftShoulder", {"upperarm"}}, {"LeftElbow", {"forearm"}},
          {"LeftWrist", {"hand"}}, {"LFingers", {"fmiddle01"}}, {"LThumb", {"thumb01"}}}},
    };
    return table;
}

bool is_separator(char c) { return c == '_' || c == '.' || c == '-' || c == ' '; }
bool is_side_letter(char c) { return c == 'l' || c == 'L' || c == 'r' || c == 'R'; }
int side_of_letter(char c) { return c == 'l' || c == 'L' ? 0 : 1; }

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// The name without namespace ("mixamorig:", "Armature|") and Rigify "DEF-" prefixes.
std::string_view strip_prefixes(std::string_view name) {
    if (const size_t p = name.find_last_of(":|"); p != std::string_view::npos) name.remove_prefix(p + 1);
    if (name.size() > 4 && name.substr(0, 3) == "DEF" && is_separator(name[3])) name.remove_prefix(4);
    return name;
}

std::string key_of(std::string_view s) {
    std::string out;
    for (char c : s)
        if (!is_separator(c)) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

struct SidedKey {
    int side;  // 0 left, 1 right
    std::string key;
};

// Every way `name` reads as a sided joint (see the header comment).
std::vector<SidedKey> sided_keys(std::string_view full) {
    const std::string_view s = strip_prefixes(full);
    const std::string lo = lower(s);
    std::vector<SidedKey> out;
    const size_t n = s.size();
    for (int side = 0; side < 2; ++side) {
        const std::string word = side == 0 ? "left" : "right";
        if (n > word.size() && lo.compare(0, word.size(), word) == 0) out.push_back({side, key_of(s.substr(word.size()))});
        if (n > word.size() && lo.compare(n - word.size(), word.size(), word) == 0)
            out.push_back({side, key_of(s.substr(0, n - word.size()))});
    }
    if (n >= 3 && is_side_letter(s[0]) && is_separator(s[1])) out.push_back({side_of_letter(s[0]), key_of(s.substr(2))});
    if (n >= 3 && is_side_letter(s[n - 1]) && is_separator(s[n - 2]))
        out.push_back({side_of_letter(s[n - 1]), key_of(s.substr(0, n - 2))});
    for (size_t i = 1; i + 2 < n; ++i)  // "J_Bip_L_Hand", "thigh.L.001" (a twist bone: key "thigh001")
        if (is_separator(s[i]) && is_side_letter(s[i + 1]) && is_separator(s[i + 2]))
            out.push_back({side_of_letter(s[i + 1]), key_of(std::string(s.substr(0, i)) + std::string(s.substr(i + 3)))});
    if (n >= 2 && is_side_letter(s[0]) && std::isupper(static_cast<unsigned char>(s[1])))
        out.push_back({side_of_letter(s[0]), key_of(s.substr(1))});
    return out;
}

// Rank of `key` in `keys` (earlier = preferred), or -1.
int rank_of(const std::vector<std::string>& keys, const std::string& key) {
    const auto it = std::find(keys.begin(), keys.end(), key);
    return it == keys.end() ? -1 : static_cast<int>(it - keys.begin());
}

// Map of one convention: for each canonical joint the best-ranked joint (shallowest on ties).
std::vector<int> match(const Convention& conv, const Skeleton& skeleton) {
    std::vector<int> joint(kCanonical.size(), -1), rank(kCanonical.size(), INT_MAX);
    std::vector<std::string> plain;
    std::vector<std::vector<SidedKey>> sided;
    for (const std::string& name : skeleton.names()) {
        plain.push_back(key_of(strip_prefixes(name)));
        sided.push_back(sided_keys(name));
    }
    for (const Row& row : conv.rows) {
        const int c = canonical_index(row.canonical);
        for (int j = 0; j < skeleton.joint_count(); ++j) {
            const auto u = static_cast<size_t>(j);
            auto offer = [&](int canonical, int r) {
                if (r < 0 || r >= rank[static_cast<size_t>(canonical)]) return;
                rank[static_cast<size_t>(canonical)] = r;
                joint[static_cast<size_t>(canonical)] = j;
            };
            if (kCanonical[static_cast<size_t>(c)].side < 0) {
                offer(c, rank_of(row.keys, plain[u]));
            } else {
                for (const SidedKey& sk : sided[u]) offer(c + sk.side, rank_of(row.keys, sk.key));
                // CMU's lowercase "lhand"/"rhand": a one-letter side before a lower-case key.
                if (row.keys.size() == 1 && plain[u].size() == row.keys[0].size() + 1 &&
                    plain[u].compare(1, std::string::npos, row.keys[0]) == 0 && is_side_letter(plain[u][0]) &&
                    std::string_view(row.canonical) == "lhand")
                    offer(c + side_of_letter(plain[u][0]), 0);
            }
        }
    }
    // One file joint answers at most one canonical joint: keep the first canonical (parents first).
    for (size_t a = 0; a < joint.size(); ++a)
        for (size_t b = a + 1; b < joint.size(); ++b)
            if (joint[a] >= 0 && joint[b] == joint[a]) joint[b] = -1;
    return joint;
}

int score(const std::vector<int>& joint) {
    int s = 0;
    for (size_t c = 0; c < joint.size(); ++c)
        if (joint[c] >= 0) s += kCanonical[c].required ? 3 : 1;
    return s;
}

}  // namespace

std::span<const CanonicalJoint> canonical_humanoid() { return kCanonical; }

int canonical_index(std::string_view name) {
    for (size_t i = 0; i < kCanonical.size(); ++i)
        if (name == kCanonical[i].name) return static_cast<int>(i);
    return -1;
}

std::string joint_name_key(std::string_view name) { return key_of(strip_prefixes(name)); }

int HumanoidMap::find(std::string_view canonical_name) const {
    const int c = canonical_index(canonical_name);
    return c < 0 || static_cast<size_t>(c) >= joint.size() ? -1 : joint[static_cast<size_t>(c)];
}

int HumanoidMap::fold(int c) const {
    while (c >= 0 && static_cast<size_t>(c) < joint.size()) {
        if (joint[static_cast<size_t>(c)] >= 0) return joint[static_cast<size_t>(c)];
        c = kCanonical[static_cast<size_t>(c)].parent;
    }
    return -1;
}

int HumanoidMap::canonical_of(int j) const {
    if (j < 0) return -1;
    for (size_t c = 0; c < joint.size(); ++c)
        if (joint[c] == j) return static_cast<int>(c);
    return -1;
}

namespace {

// Puts skeleton joint `j` at canonical joint `c`, taking it from any other canonical joint.
void assign(HumanoidMap& map, size_t c, int j) {
    for (size_t other = 0; other < map.joint.size(); ++other)
        if (map.joint[other] == j && other != c) {
            map.joint[other] = -1;
            map.from_declared[other] = false;
        }
    map.joint[c] = j;
}

}  // namespace

Result<HumanoidMap> map_humanoid(const Skeleton& skeleton, const std::map<std::string, std::string>& explicit_map,
                                 const std::string& source, const std::string& where, const DeclaredHumanoid& declared) {
    HumanoidMap map;
    map.joint.assign(kCanonical.size(), -1);
    int best = 0;
    for (const Convention& conv : conventions()) {
        std::vector<int> joint = match(conv, skeleton);
        const int s = score(joint);
        if (s > best) {
            best = s;
            map.joint = std::move(joint);
            map.convention = conv.name;
        }
    }
    map.from_explicit.assign(kCanonical.size(), false);
    map.from_declared.assign(kCanonical.size(), false);
    for (const auto& [canonical, file_name] : declared.joints) {
        const int c = canonical_index(canonical);
        const int j = skeleton.find(file_name);
        if (c < 0 || j < 0) continue;
        assign(map, static_cast<size_t>(c), j);
        map.from_declared[static_cast<size_t>(c)] = true;
    }
    if (!declared.joints.empty()) {
        bool by_name = false;
        for (size_t c = 0; c < kCanonical.size(); ++c) by_name |= map.joint[c] >= 0 && !map.from_declared[c];
        map.convention = declared.origin + (by_name && !map.convention.empty() ? " + " + map.convention + " names" : "");
    }
    for (const auto& [canonical, file_name] : explicit_map) {
        const std::string at = where + "/" + canonical;
        const int c = canonical_index(canonical);
        if (c < 0) return make_error(source, "'" + canonical + "' is not a canonical humanoid joint (see docs/CHARACTERS.md)", 0, 0, at);
        const int j = skeleton.find(file_name);
        if (j < 0) return make_error(source, "joint '" + file_name + "' is not in the skeleton", 0, 0, at);
        for (size_t other = 0; other < map.joint.size(); ++other)
            if (map.joint[other] == j && static_cast<int>(other) != c && map.from_explicit[other])
                return make_error(source, "joint '" + file_name + "' is already given for '" + kCanonical[other].name + "'", 0, 0, at);
        assign(map, static_cast<size_t>(c), j);  // the explicit entry wins over the convention's or file's
        map.from_explicit[static_cast<size_t>(c)] = true;
        map.from_declared[static_cast<size_t>(c)] = false;
    }
    if (!explicit_map.empty()) map.convention = map.convention.empty() ? "explicit humanoid_map" : map.convention + " + humanoid_map";
    for (size_t c = 0; c < kCanonical.size(); ++c)
        if (kCanonical[c].required && map.joint[c] < 0) map.missing.push_back(kCanonical[c].name);
    map.humanoid = map.missing.empty();
    return map;
}

std::string canonical_of_humanoid_bone(std::string_view bone, bool vrm1) {
    const std::string key = key_of(bone);
    for (int side = 0; side < 2; ++side) {
        const std::string word = side == 0 ? "left" : "right";
        if (key.size() <= word.size() || key.compare(0, word.size(), word) != 0) continue;
        const std::string rest = key.substr(word.size());
        // VRM 1.0 renamed the thumb: Metacarpal, Proximal, Distal (VRM 0.x: Proximal, Intermediate, Distal).
        if (rest == (vrm1 ? "thumbmetacarpal" : "thumbproximal")) return kCanonical[static_cast<size_t>(canonical_index("LThumb") + side)].name;
        if (rest.rfind("thumb", 0) == 0) return "";
        for (const Row& row : unity_rows("", ""))
            if (kCanonical[static_cast<size_t>(canonical_index(row.canonical))].side == 0 && row.keys.front() == rest)
                return kCanonical[static_cast<size_t>(canonical_index(row.canonical) + side)].name;
        return "";
    }
    for (const Row& row : unity_rows("", ""))
        if (kCanonical[static_cast<size_t>(canonical_index(row.canonical))].side < 0 && row.keys.front() == key) return row.canonical;
    return "";
}

std::vector<std::string> unmapped_joints(const Skeleton& skeleton, const HumanoidMap& map) {
    std::vector<std::string> out;
    for (int j = 0; j < skeleton.joint_count(); ++j)
        if (map.canonical_of(j) < 0) out.push_back(skeleton.names()[static_cast<size_t>(j)]);
    return out;
}

int find_joint(const Skeleton& skeleton, const HumanoidMap& map, std::string_view name) {
    if (const int j = map.find(name); j >= 0) return j;
    return skeleton.find(name);
}

}  // namespace aloha
