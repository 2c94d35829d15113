# Imports bw-export's files into Blender and checks what Blender makes of them:
#   blender -b --factory-startup --python-exit-code 1 --python blender_check.py -- \
#     --glb solids.glb --vdb water_000003.vdb [--expect expect.json]
# Checks that every glTF node became a mesh object, that the animation spans the
# frames the file says it holds (with the scene's frame rate set to the run's, so
# Blender frame F is run frame F), that the VDB gives a volume with a grid "surface",
# and, with --expect (written from the run's frame files), that the named bodies have
# the expected world matrix (breakwater coordinates, z-up) or are hidden (scale 0) at
# the given frames, and that the scene's camera stands, looks and zooms as bw-render's
# at the given frames. Prints one line "blender-check: ..." and raises on a mismatch,
# so Blender exits with 1.
import json
import os
import struct
import sys

import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_camera import camera_matches, camera_view_error  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
args = {}
for i in range(0, len(argv) - 1, 2):
    args[argv[i].lstrip("-")] = argv[i + 1]


def fail(message):
    print("blender-check: FAIL " + message)
    sys.stdout.flush()
    raise RuntimeError(message)


def glb_json(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, _ = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67 or version != 2:
        fail(f"{path}: not a glTF 2.0 binary file")
    length, kind = struct.unpack_from("<II", data, 12)
    if kind != 0x4E4F534A:
        fail(f"{path}: the first chunk is not JSON")
    return json.loads(data[20:20 + length])


expect = {}
if "expect" in args:
    with open(args["expect"]) as f:
        expect = json.load(f)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
report = []

if "glb" in args:
    gltf = glb_json(args["glb"])
    fps = int(expect.get("fps", args.get("fps", 30)))
    # The importer turns glTF seconds into frames with the scene's rate.
    scene.render.fps = fps
    scene.render.fps_base = 1.0
    # Shading "NORMALS", the importer's default, fails in Debian 12's Blender 3.4 with
    # its numpy 1.24 (np.bool); the solids are flat-faced anyway.
    bpy.ops.import_scene.gltf(filepath=args["glb"], import_shading="FLAT")
    meshes = [o for o in scene.objects if o.type == "MESH"]
    nodes = len([n for n in gltf.get("nodes", []) if "mesh" in n])
    want = int(expect.get("objects", nodes))
    if len(meshes) != want:
        fail(f"{len(meshes)} mesh objects, expected {want}")
    report.append(f"objects {len(meshes)}")
    ranges = [a.frame_range for a in bpy.data.actions]
    if ranges:
        first = min(r[0] for r in ranges)
        last = max(r[1] for r in ranges)
        report.append(f"animation {first:g}..{last:g} at {fps} fps")
        frames = expect.get("frames", gltf["asset"].get("extras", {}).get("frames"))
        if frames and (abs(first - frames[0]) > 1e-3 or abs(last - frames[1]) > 1e-3):
            fail(f"animation spans frames {first:g}..{last:g}, expected {frames[0]}..{frames[1]}")
    elif expect.get("frames"):
        fail("no animation was imported")
    for pose in expect.get("poses", []):
        obj = bpy.data.objects.get(pose["name"])
        if obj is None:
            fail(f"no object named {pose['name']!r}")
        if "body" in pose and obj.get("body") != pose["body"]:
            fail(f"{pose['name']}: custom property body is {obj.get('body')}, expected {pose['body']}")
        scene.frame_set(int(pose["frame"]))
        m = obj.matrix_world
        if pose.get("hidden"):
            s = max(abs(v) for v in obj.scale)
            if s > 1e-6:
                fail(f"{pose['name']} at frame {pose['frame']}: scale {tuple(obj.scale)}, expected 0 (hidden)")
            report.append(f"{pose['name']}@{pose['frame']} hidden")
            continue
        error = max(abs(m[r][c] - pose["matrix"][r][c]) for r in range(3) for c in range(4))
        if error > float(pose.get("tolerance", 1e-4)):
            fail(f"{pose['name']} at frame {pose['frame']}: world matrix {[list(row) for row in m]} differs from "
                 f"{pose['matrix']} by {error:.3g}")
        report.append(f"{pose['name']}@{pose['frame']} pose error {error:.2g}")

    cameras = [o for o in scene.objects if o.type == "CAMERA"]
    if len(cameras) != len(gltf.get("cameras", [])):
        fail(f"{len(cameras)} camera objects, the file has {len(gltf.get('cameras', []))}")
    for view in expect.get("camera", []):
        if len(cameras) != 1:
            fail(f"{len(cameras)} camera objects, expected 1")
        error, fov_error, got = camera_view_error(scene, cameras[0], view)
        if not camera_matches(error, fov_error):
            fail(f"camera at frame {view['frame']}: {got}; expected {view}")
        report.append(f"camera@{view['frame']} error {error:.2g}")

if "vdb" in args:
    path = os.path.abspath(args["vdb"])
    before = set(scene.objects)
    bpy.ops.object.volume_import(filepath=path, directory=os.path.dirname(path),
                                 files=[{"name": os.path.basename(path)}])
    volumes = [o for o in scene.objects if o not in before and o.type == "VOLUME"]
    if len(volumes) != 1:
        fail(f"{path}: Blender made {len(volumes)} volume objects, expected 1")
    grids = volumes[0].data.grids
    if not grids.load():
        fail(f"{path}: Blender cannot load the grids: {grids.error_message}")
    names = [g.name for g in grids]
    for name in expect.get("grids", ["surface"]):
        if name not in names:
            fail(f"{path}: no grid {name!r} among {names}")
    report.append("volume grids " + ",".join(names))

print("blender-check: ok " + "; ".join(report))
