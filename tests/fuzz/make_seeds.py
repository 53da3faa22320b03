# Regenerates the seed corpora under tests/fuzz/corpus/ from the shipped data files (python3 make_seeds.py).
import struct, json, base64, os, sys
root = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
C = root + '/tests/fuzz/corpus'
def w(target, name, data):
    if isinstance(data, str): data = data.encode()
    open(f'{C}/{target}/{name}', 'wb').write(data)

# ---------- glTF: the two-joint model of gltf_errors_test.cpp ----------
b = b''
b += struct.pack('<9f', 0,0,0, 1,0,0, 0,-1,0)
b += struct.pack('<12H', 0,0,0,0, 1,0,0,0, 1,0,0,0)
b += struct.pack('<12f', 1,0,0,0, 2,0,0,0, .5,.5,0,0)
b += struct.pack('<4H', 0,1,2,0)
b += struct.pack('<16f', 1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1)
b += struct.pack('<16f', 1,0,0,0, 0,1,0,0, 0,0,1,0, 0,.5,0,1)
b += struct.pack('<2f', 1, 2)
b += struct.pack('<8f', 0,0,0,1, 0.38268343,0,0,0.92387953)
def model(uri):
    buf = {"byteLength": len(b)}
    if uri: buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(b).decode()
    return {
     "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 2]}],
     "nodes": [{"name": "hip", "children": [1]}, {"name": "knee", "translation": [0, -0.5, 0]},
               {"name": "body", "mesh": 0, "skin": 0, "translation": [5, 0, 0]}],
     "skins": [{"joints": [0, 1], "inverseBindMatrices": 4}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "JOINTS_0": 1, "WEIGHTS_0": 2}, "indices": 3}]}],
     "buffers": [buf],
     "bufferViews": [{"buffer": 0, "byteOffset": o, "byteLength": l} for o, l in
                     [(0,36),(36,24),(60,48),(108,6),(116,128),(244,8),(252,32)]],
     "accessors": [
       {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
       {"bufferView": 1, "componentType": 5123, "count": 3, "type": "VEC4"},
       {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC4"},
       {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"},
       {"bufferView": 4, "componentType": 5126, "count": 2, "type": "MAT4"},
       {"bufferView": 5, "componentType": 5126, "count": 2, "type": "SCALAR"},
       {"bufferView": 6, "componentType": 5126, "count": 2, "type": "VEC4"}],
     "animations": [{"name": "bend", "samplers": [{"input": 5, "output": 6, "interpolation": "STEP"}],
                     "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                                  {"sampler": 0, "target": {"node": 2, "path": "rotation"}}]}]}
def glb(js, binchunk):
    jb = json.dumps(js, separators=(',', ':')).encode()
    jb += b' ' * ((4 - len(jb) % 4) % 4)
    bb = binchunk + b'\0' * ((4 - len(binchunk) % 4) % 4)
    body = struct.pack('<II', len(jb), 0x4E4F534A) + jb
    if binchunk is not None: body += struct.pack('<II', len(bb), 0x004E4942) + bb
    return struct.pack('<III', 0x46546C67, 2, 12 + len(body)) + body
m = model(True)
w('fuzz_gltf', 'two_joints.gltf', json.dumps(m, indent=1))
w('fuzz_gltf', 'two_joints.glb', glb(model(False), b))
w('fuzz_gltf', 'two_joints_truncated.glb', glb(model(False), b)[:200])
mm = model(True); mm['animations'][0]['samplers'][0]['interpolation'] = 'CUBICSPLINE'
w('fuzz_gltf', 'cubic.gltf', json.dumps(mm))
mm = model(True); mm['nodes'][1]['children'] = [0]
w('fuzz_gltf', 'cycle.gltf', json.dumps(mm))
mm = model(True); mm['accessors'][0]['count'] = 1000000000
w('fuzz_gltf', 'huge_count.gltf', json.dumps(mm))
mm = model(True); mm['nodes'][0]['matrix'] = [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,1,0,1]; mm['nodes'][0]['scale'] = [2,2,2]
w('fuzz_gltf', 'matrix_and_scale.gltf', json.dumps(mm))
w('fuzz_gltf', 'empty.gltf', '{"asset": {"version": "2.0"}}')
# CesiumMan's JSON chunk with only 1 KiB of its binary chunk (every accessor past the end).
cm = open(root + '/data/characters/CesiumMan.glb', 'rb').read()
jlen = struct.unpack('<I', cm[12:16])[0]
cj = json.loads(cm[20:20 + jlen])
cj.get('images', []).clear(); cj.pop('textures', None); cj.pop('samplers', None)
for mat in cj.get('materials', []): mat.pop('pbrMetallicRoughness', None)
w('fuzz_gltf', 'cesium_json_short_bin.glb', glb(cj, cm[28 + jlen:28 + jlen + 1024]))

# ---------- BVH ----------
bvh = open(root + '/data/characters/131_01.bvh').read().split('\n')
mi = bvh.index('MOTION')
head = bvh[:mi + 1]
frames = bvh[mi + 3: mi + 6]
w('fuzz_bvh', 'cmu_3frames.bvh', '\n'.join(head + ['Frames: 3', 'Frame Time: .0083333'] + frames) + '\n')
w('fuzz_bvh', 'cmu_hierarchy_cut.bvh', '\n'.join(bvh[:60]) + '\n')
w('fuzz_bvh', 'cmu_frame_cut.bvh', '\n'.join(head + ['Frames: 3', 'Frame Time: .0083333'] + frames[:2]) + '\n' + frames[2][:100])
small = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Spine
  {
    OFFSET 0 5 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    End Site
    {
      OFFSET 0 3 0
    }
  }
}
MOTION
Frames: 2
Frame Time: 0.033333
0 10 0 0 0 0 10 0 0
1 10 0 5 0 0 20 0 0
"""
w('fuzz_bvh', 'two_joints.bvh', small)
w('fuzz_bvh', 'wrong_channel_count.bvh', small.replace('CHANNELS 3 Z', 'CHANNELS 4 Z'))
w('fuzz_bvh', 'short_frame.bvh', small.replace('1 10 0 5 0 0 20 0 0', '1 10 0 5 0 0 20'))
w('fuzz_bvh', 'nan_value.bvh', small.replace('1 10 0 5', '1 nan 0 inf'))
w('fuzz_bvh', 'huge_frames.bvh', small.replace('Frames: 2', 'Frames: 1000000000'))
w('fuzz_bvh', 'crlf.bvh', small.replace('\n', '\r\n'))

# ---------- rules ----------
rules = open(root + '/data/rules/default.json').read()
w('fuzz_rules', 'default.json', rules)
w('fuzz_rules', 'default_truncated.json', rules[:len(rules) // 2])
w('fuzz_rules', 'small.json', json.dumps({
  "geometric_levels": [{"name": "full", "method": "layered"}, {"name": "proxy", "method": "rigid_proxy"}],
  "animation_levels": [{"name": "ik", "walk": "kinematic", "ik": "ccd", "ik_iterations": 4}, {"name": "clip", "walk": "clip"}],
  "rules": [{"name": "near", "when": {"distance": {"lt": 10}, "any": [{"visible": True}, {"importance": {"ge": 0.5}}]},
             "then": {"geometry": "full", "animation": "ik"}},
            {"name": "rest", "then": {"geometry": "proxy", "animation": "clip"}}]}, indent=1))

# ---------- scenes ----------
for f in sorted(os.listdir(root + '/data/scenes')):
    if f in ('closeup.json', 'crowd_1k.json'):
        w('fuzz_scene', f, open(root + '/data/scenes/' + f).read())
w('fuzz_scene', 'keys_types.json', json.dumps({
  "name": "t", "frames": 10, "camera": {"keys": [{"time": 0, "position": [0, 2, 10], "target": [0, 1, 0]},
                                                 {"time": 1, "position": [1, 2, 10], "target": [0, 1, 0]}]},
  "character_types": [{"name": "man", "gltf": "builtin:cesium_man"},
                      {"name": "humanoid", "bvh": "builtin:humanoid", "muscles": "builtin:humanoid_muscles", "limits": "builtin:humanoid_limits"}],
  "paths": [{"name": "p", "points": [[0, 0, 0], [1, 0, 1]]}],
  "characters": [{"type": "man", "requests": [{"type": "look_at", "target": [0, 1, 5]}, {"type": "rest"}]}],
  "crowds": [{"type": "humanoid", "count": 5, "layout": "disc", "radius": 3, "clip": "humanoid.mocap"}]}))
w('fuzz_scene', 'escape.json', '{"camera": {"position": [0,2,10], "target": [0,1,0]}, "characters": [{}], "rules": "../../../etc/passwd"}')

# ---------- joint limits ----------
w('fuzz_joint_limits', 'humanoid_limits.json', open(root + '/data/characters/humanoid_limits.json').read())
w('fuzz_joint_limits', 'radians.json', '{"units": "radians", "joints": {"A": {"min": [-1, 0, 0], "max": [1, 0.5, 0]}}}')
