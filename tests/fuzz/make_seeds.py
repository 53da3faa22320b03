# Regenerates the seed corpora under tests/fuzz/corpus/ (python3 make_seeds.py). Every seed is written from
# this script's own data or from the project's data files (rules, scenes, joint limits); none is cut from a
# third-party asset (no motion-capture BVH or sample glTF model is read).
import struct, json, base64, math, os, sys
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

# ---------- glTF: a skinned chain character, the shape of an exported game character ----------
# A Z-up matrix node over an armature node over a chain of 8 joints listed in a skin order that is not
# depth-first; a 12-sided tube of 9 rings skinned to them (positions, normals, JOINTS_0, WEIGHTS_0,
# indices), a material, and one LINEAR clip of 24 keys with rotation, translation and scale channels on
# every joint. chain_skinned.glb is the whole model; chain_json_short_bin.glb keeps its JSON chunk
# (7.4 KiB) with only the first 1 KiB of its 14 KiB binary chunk, so every later accessor points past
# the end of the data.
def chain_character():
    joints, sides, rings, keys = 8, 12, 9, 24
    seg = 0.2
    bv, acc, blob = [], [], bytearray()
    def add(data, ctype, count, typ, target=None, minmax=None):
        while len(blob) % 4: blob.append(0)
        view = {"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)}
        if target: view["target"] = target
        bv.append(view); blob.extend(data)
        a = {"bufferView": len(bv) - 1, "componentType": ctype, "count": count, "type": typ}
        if minmax: a["min"], a["max"] = minmax
        acc.append(a)
        return len(acc) - 1
    pos, nrm, jnt, wgt = [], [], [], []
    for r in range(rings):
        y = r * seg * (joints - 1) / (rings - 1)
        k = min(int(y / seg), joints - 2)
        f = y / seg - k
        for s_ in range(sides):
            a = 2 * math.pi * s_ / sides
            pos += [0.08 * math.cos(a), y, 0.08 * math.sin(a)]
            nrm += [math.cos(a), 0.0, math.sin(a)]
            jnt += [k, k + 1, 0, 0]
            wgt += [1 - f, f, 0.0, 0.0]
    idx = []
    for r in range(rings - 1):
        for s_ in range(sides):
            a0, a1 = r * sides + s_, r * sides + (s_ + 1) % sides
            b0, b1 = a0 + sides, a1 + sides
            idx += [a0, b0, a1, a1, b0, b1]
    nv = rings * sides
    p_acc = add(struct.pack(f'<{len(pos)}f', *pos), 5126, nv, 'VEC3', 34962,
                ([-0.08, 0.0, -0.08], [0.08, seg * (joints - 1), 0.08]))
    n_acc = add(struct.pack(f'<{len(nrm)}f', *nrm), 5126, nv, 'VEC3', 34962)
    j_acc = add(struct.pack(f'<{len(jnt)}H', *jnt), 5123, nv, 'VEC4', 34962)
    w_acc = add(struct.pack(f'<{len(wgt)}f', *wgt), 5126, nv, 'VEC4', 34962)
    i_acc = add(struct.pack(f'<{len(idx)}H', *idx), 5123, len(idx), 'SCALAR', 34963)
    # Skin order (not depth-first): joint k of the chain is skin slot order[k].
    order = [0, 2, 4, 6, 1, 3, 5, 7]
    ibm = []
    for slot in range(joints):
        k = order.index(slot)
        ibm += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -seg * k, 0, 1]
    ibm_acc = add(struct.pack('<128f', *ibm), 5126, joints, 'MAT4')
    times = [(t + 1) / keys for t in range(keys)]
    t_acc = add(struct.pack(f'<{keys}f', *times), 5126, keys, 'SCALAR', None, ([times[0]], [times[-1]]))
    samplers, channels = [], []
    for k in range(joints):
        rot, tr, sc = [], [], []
        for t in range(keys):
            ang = 0.3 * math.sin(2 * math.pi * t / keys + 0.5 * k)
            ax = [1.0, 0.0, 0.0] if k % 2 else [0.0, 0.0, 1.0]
            rot += [math.sin(ang / 2) * ax[0], math.sin(ang / 2) * ax[1], math.sin(ang / 2) * ax[2], math.cos(ang / 2)]
            tr += [0.0, seg if k else 0.01 * math.sin(2 * math.pi * t / keys), 0.0]
            sc += [1.0, 1.0 + 0.02 * math.sin(2 * math.pi * t / keys), 1.0]
        for path, data, typ in (('rotation', rot, 'VEC4'), ('translation', tr, 'VEC3'), ('scale', sc, 'VEC3')):
            out = add(struct.pack(f'<{len(data)}f', *data), 5126, keys, typ)
            samplers.append({"input": t_acc, "output": out, "interpolation": "LINEAR"})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": 3 + k, "path": path}})
    nodes = [{"name": "Z_UP", "children": [1], "matrix": [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1]},
             {"name": "Armature", "children": [3, 2], "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]},
             {"name": "tube", "mesh": 0, "skin": 0}]
    for k in range(joints):
        n = {"name": f"chain_joint_{k}", "translation": [0.0, seg if k else 0.0, 0.0], "rotation": [0, 0, 0, 1]}
        if k + 1 < joints: n["children"] = [4 + k]
        nodes.append(n)
    js = {"asset": {"version": "2.0", "generator": "tests/fuzz/make_seeds.py"}, "scene": 0,
          "scenes": [{"nodes": [0]}], "nodes": nodes,
          "skins": [{"name": "chain", "inverseBindMatrices": ibm_acc, "skeleton": 3,
                     "joints": [3 + order.index(slot) for slot in range(joints)]}],
          "materials": [{"name": "skin", "pbrMetallicRoughness": {"baseColorFactor": [0.86, 0.68, 0.56, 1.0],
                                                                  "metallicFactor": 0.0, "roughnessFactor": 0.8}}],
          "meshes": [{"name": "tube", "primitives": [{
              "attributes": {"POSITION": p_acc, "NORMAL": n_acc, "JOINTS_0": j_acc, "WEIGHTS_0": w_acc},
              "indices": i_acc, "material": 0, "mode": 4}]}],
          "animations": [{"name": "sway", "samplers": samplers, "channels": channels}],
          "buffers": [{"byteLength": len(blob)}], "bufferViews": bv, "accessors": acc}
    return js, bytes(blob)
cj, cb = chain_character()
w('fuzz_gltf', 'chain_skinned.glb', glb(cj, cb))
w('fuzz_gltf', 'chain_json_short_bin.glb', glb(cj, cb[:1024]))
# The same character declaring a VRM humanoid (VRM 1.0's object form and VRM 0.x's array form), with a bone
# that is no canonical joint (a finger) and one on a node outside the skin (an eye on the Armature node).
import copy
vrm_bones = {'hips': 3, 'spine': 4, 'chest': 5, 'neck': 6, 'head': 7, 'leftIndexProximal': 8, 'leftEye': 1}
vj = copy.deepcopy(cj)
vj['extensionsUsed'] = ['VRMC_vrm']
vj['extensions'] = {'VRMC_vrm': {'specVersion': '1.0', 'humanoid': {'humanBones': {b: {'node': n} for b, n in vrm_bones.items()}}}}
w('fuzz_gltf', 'chain_vrm1.glb', glb(vj, cb))
vj = copy.deepcopy(cj)
vj['extensionsUsed'] = ['VRM']
vj['extensions'] = {'VRM': {'humanoid': {'humanBones': [{'bone': b, 'node': n} for b, n in vrm_bones.items()]}}}
w('fuzz_gltf', 'chain_vrm0.glb', glb(vj, cb))
# The same character without its skin (a rigid figure): the loader makes the scene's nodes its skeleton.
vj = copy.deepcopy(cj)
del vj['skins']
del vj['nodes'][2]['skin']
w('fuzz_gltf', 'chain_rigid.glb', glb(vj, cb))
# The same character with vertex colours, UVs and every material map the loader draws (a 2 x 2 PNG as base
# colour, normal, occlusion and emissive texture; factors and KHR_materials_emissive_strength).
def with_maps(js, blob):
    import zlib
    js, blob = copy.deepcopy(js), bytearray(blob)
    def view(data):
        while len(blob) % 4: blob.append(0)
        js['bufferViews'].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        blob.extend(data)
        return len(js['bufferViews']) - 1
    def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    raw = b''.join(b'\x00' + bytes(row) for row in ([200, 128, 230, 255, 90, 128, 240, 255], [128, 60, 220, 255, 128, 200, 200, 255]))
    png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 2, 2, 8, 6, 0, 0, 0)) + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b'')
    prim = js['meshes'][0]['primitives'][0]
    nv = js['accessors'][prim['attributes']['POSITION']]['count']
    colours = bytes((37 * v + c * 80) % 256 if c < 3 else 255 for v in range(nv) for c in range(4))
    uvs = struct.pack(f'<{2 * nv}f', *[x for v in range(nv) for x in ((v % 12) / 12.0, (v // 12) / 8.0)])
    js['accessors'].append({"bufferView": view(colours), "componentType": 5121, "normalized": True, "count": nv, "type": "VEC4"})
    prim['attributes']['COLOR_0'] = len(js['accessors']) - 1
    js['accessors'].append({"bufferView": view(uvs), "componentType": 5126, "count": nv, "type": "VEC2"})
    prim['attributes']['TEXCOORD_0'] = len(js['accessors']) - 1
    js['images'] = [{"bufferView": view(png), "mimeType": "image/png"}]
    js['textures'] = [{"source": 0}]
    js['extensionsUsed'] = ['KHR_materials_emissive_strength']
    js['materials'][0].update({"normalTexture": {"index": 0, "scale": 0.7}, "occlusionTexture": {"index": 0, "strength": 0.5},
                               "emissiveTexture": {"index": 0}, "emissiveFactor": [0.2, 0.1, 0.0],
                               "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 2.0}}})
    js['materials'][0]['pbrMetallicRoughness'].update({"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 0},
                                                       "metallicFactor": 0.6, "roughnessFactor": 0.4})
    js['buffers'][0]['byteLength'] = len(blob)
    return js, bytes(blob)
mj, mb = with_maps(cj, cb)
w('fuzz_gltf', 'chain_maps.glb', glb(mj, mb))
# The same character as gltfpack writes it (KHR_mesh_quantization + KHR_texture_transform, and
# EXT_meshopt_compression with its filters), when gltfpack (Debian package gltfpack) is installed.
import shutil, subprocess, tempfile
if shutil.which('gltfpack'):
    with tempfile.TemporaryDirectory() as tmp:
        open(f'{tmp}/in.glb', 'wb').write(glb(cj, cb))
        for flags, name in (([], 'chain_quantised.glb'), (['-c'], 'chain_meshopt.glb')):
            subprocess.run(['gltfpack', '-i', f'{tmp}/in.glb', '-o', f'{tmp}/{name}'] + flags, check=True, capture_output=True)
            w('fuzz_gltf', name, open(f'{tmp}/{name}', 'rb').read())
else:
    print('make_seeds: gltfpack not found; chain_quantised.glb and chain_meshopt.glb not rewritten', file=sys.stderr)

# ---------- BVH ----------
# A 12-joint body written here (offsets in centimetres, tab indents, CR LF lines like exported mocap), with
# a different rotation order on each limb, a zero-length joint, End Sites, and 3 frames of values; then the
# same file cut inside the hierarchy and inside the last motion row.
body = [  # name, parent, offset (cm), rotation order
    ('Hips', None, (0, 0, 0), 'ZYX'),
    ('LeftUpLeg', 'Hips', (9, -6, 0), 'ZXY'), ('LeftLeg', 'LeftUpLeg', (0, -42, 0), 'XYZ'),
    ('LeftFoot', 'LeftLeg', (0, -41, 0), 'YXZ'),
    ('RightUpLeg', 'Hips', (-9, -6, 0), 'ZYX'), ('RightLeg', 'RightUpLeg', (0, -42, 0), 'XZY'),
    ('RightFoot', 'RightLeg', (0, -41, 0), 'YZX'),
    ('Spine', 'Hips', (0, 10, 0), 'ZXY'), ('SpineRoot', 'Spine', (0, 0, 0), 'ZXY'),
    ('Chest', 'SpineRoot', (0, 25, 2), 'ZXY'), ('Neck', 'Chest', (0, 20, 0), 'ZXY'), ('Head', 'Neck', (0, 9, 1), 'ZXY')]
ends = {'LeftFoot': (0, -5, 14), 'RightFoot': (0, -5, 14), 'Head': (0, 18, 0)}
def bvh_joint(i, depth):
    name, _, off, order = body[i]
    t = '\t' * depth
    out = [t + ('ROOT ' if depth == 0 else 'JOINT ') + name, t + '{', t + '\tOFFSET %.5f %.5f %.5f' % off]
    rot = ' '.join(a + 'rotation' for a in order)
    out.append(t + '\tCHANNELS ' + ('6 Xposition Yposition Zposition ' if depth == 0 else '3 ') + rot)
    for k, j in enumerate(body):
        if j[1] == name: out += bvh_joint(k, depth + 1)
    if name in ends: out += [t + '\tEnd Site', t + '\t{', t + '\t\tOFFSET %.5f %.5f %.5f' % ends[name], t + '\t}']
    return out + [t + '}']
hier = ['HIERARCHY'] + bvh_joint(0, 0)
rows = []
for f in range(3):
    v = [1.5 * f, 94.0 + 0.5 * f, 12.0 * f]
    for k in range(len(body)):
        v += [round(20 * math.sin(0.9 * k + 0.4 * f + a), 4) for a in (0.0, 1.3, 2.6)]
    rows.append(' '.join('%.4f' % x for x in v))
motion = ['MOTION', 'Frames: 3', 'Frame Time: .0333333']
crlf = lambda lines: '\r\n'.join(lines) + '\r\n'
w('fuzz_bvh', 'body_3frames.bvh', crlf(hier + motion + rows))
w('fuzz_bvh', 'body_hierarchy_cut.bvh', crlf(hier[:len(hier) * 3 // 5]))
w('fuzz_bvh', 'body_frame_cut.bvh', crlf(hier + motion + rows[:2]) + rows[2][:100])
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
  "character_types": [{"name": "humanoid", "humanoid": "builtin:humanoid",
                       "motions": [{"bvh": "walk.bvh", "name": "walk", "walk": True, "scale": 0.01, "humanoid_map": {"Hips": "pelvis"}},
                                   {"gltf": "anims.glb", "clip": "Wave"}]},
                      {"name": "h2", "humanoid": "builtin:humanoid", "height": 1.6, "build": 0.2}],
  "paths": [{"name": "p", "points": [[0, 0, 0], [1, 0, 1]]}],
  "characters": [{"type": "h2", "requests": [{"type": "look_at", "target": [0, 1, 5]}, {"type": "rest"}]}],
  "crowds": [{"type": "humanoid", "count": 5, "layout": "disc", "radius": 3, "clip": "humanoid.idle",
              "height": [1.55, 1.95], "build": [0.0, 1.0], "variants": 4}]}))
w('fuzz_scene', 'escape.json', '{"camera": {"position": [0,2,10], "target": [0,1,0]}, "characters": [{}], "rules": "../../../etc/passwd"}')

# ---------- joint limits ----------
w('fuzz_joint_limits', 'humanoid_limits.json', open(root + '/data/characters/humanoid_limits.json').read())
w('fuzz_joint_limits', 'radians.json', '{"units": "radians", "joints": {"A": {"min": [-1, 0, 0], "max": [1, 0.5, 0]}}}')
