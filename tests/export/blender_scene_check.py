# Checks a .blend saved by bw-export's blender_scene.py against what the run says:
#   blender -b RUN.blend --python-exit-code 1 --python blender_scene_check.py -- --expect expect.json
# or runs the script as Blender's text editor does (Text > Open, Run Script) in the
# startup file, which it must keep, and checks the scene it adds to:
#   blender -b --factory-startup --python-exit-code 1 --python blender_scene_check.py -- \
#     --expect expect.json --run-as-text export/blender_scene.py
# expect.json may give: "fps" (the run's frame rate), "frames" [first, last] (the
# scene's frame range), "resolution" [width, height], "objects" (mesh objects from
# solids.glb, plus the water's surface), "camera" (the scene camera's place, view, up
# and field of view at frames, as blender_check.py checks them), and "water": per
# frame the VDB file Blender reads there and bw-export's OBJ mesh of the same level
# set, whose volume and bounds Blender's surface (its Volume to Mesh modifier) must
# have. Prints one line "blender-scene-check: ..." and raises on a mismatch.
import json
import os
import sys

import bmesh
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_camera import camera_matches, camera_view_error  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
with open(argv[argv.index("--expect") + 1]) as f:
    expect = json.load(f)
report = []
if "--run-as-text" in argv:
    before = sorted(o.name for o in bpy.context.scene.objects)
    text = bpy.data.texts.load(argv[argv.index("--run-as-text") + 1])
    with bpy.context.temp_override(edit_text=text):
        bpy.ops.text.run_script()
    kept = [name for name in before if name in bpy.context.scene.objects]
    if kept != before:
        print("blender-scene-check: FAIL the text editor's run removed " + str(sorted(set(before) - set(kept))))
        raise RuntimeError("startup objects removed")
    report.append(f"run as text, kept {', '.join(before)}")
scene = bpy.context.scene


def fail(message):
    print("blender-scene-check: FAIL " + message)
    sys.stdout.flush()
    raise RuntimeError(message)


def obj_volume_and_bounds(path):
    """Signed volume and bounding box of an OBJ's triangles and polygons (fan-split)."""
    vertices, volume = [], 0.0
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                idx = [int(p.split("/")[0]) - 1 for p in parts[1:]]
                a = vertices[idx[0]]
                for k in range(1, len(idx) - 1):
                    b, c = vertices[idx[k]], vertices[idx[k + 1]]
                    volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                               a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
    lo = [min(v[i] for v in vertices) for i in range(3)]
    hi = [max(v[i] for v in vertices) for i in range(3)]
    return volume, lo, hi


if "fps" in expect:
    rate = scene.render.fps / scene.render.fps_base
    if abs(rate - expect["fps"]) > 1e-9 * expect["fps"]:
        fail(f"frame rate {rate:g}, expected {expect['fps']:g}")
    report.append(f"{rate:g} fps")
if "frames" in expect:
    got = [scene.frame_start, scene.frame_end]
    if got != expect["frames"]:
        fail(f"frames {got}, expected {expect['frames']}")
    report.append(f"frames {got[0]}..{got[1]}")
if "resolution" in expect:
    got = [scene.render.resolution_x, scene.render.resolution_y]
    if got != expect["resolution"] or scene.render.resolution_percentage != 100:
        fail(f"resolution {got} at {scene.render.resolution_percentage}%, expected {expect['resolution']}")
if "objects" in expect:
    meshes = [o for o in scene.objects if o.type == "MESH"]
    if len(meshes) != expect["objects"]:
        fail(f"{len(meshes)} mesh objects, expected {expect['objects']}")
    report.append(f"objects {len(meshes)}")

for view in expect.get("camera", []):
    camera = scene.camera
    if camera is None or camera.type != "CAMERA":
        fail("the scene has no camera")
    error, fov_error, got = camera_view_error(scene, camera, view)
    if not camera_matches(error, fov_error):
        fail(f"scene camera at frame {view['frame']}: {got}; expected {view}")
    report.append(f"camera@{view['frame']} error {error:.2g}")

water = bpy.data.objects.get("water")
grids = bpy.data.objects.get("water grids")
for w in expect.get("water", []):
    if water is None or grids is None:
        fail("no objects 'water' and 'water grids'")
    frame = int(w["frame"])
    scene.frame_set(frame)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    path = grids.evaluated_get(depsgraph).data.grids.frame_filepath
    if "file" in w and os.path.basename(path) != w["file"]:
        fail(f"frame {frame}: Blender reads {path!r}, expected {w['file']}")
    evaluated = water.evaluated_get(depsgraph)
    mesh = evaluated.to_mesh()
    if len(mesh.vertices) == 0:
        fail(f"frame {frame}: the water's surface is empty")
    bm = bmesh.new()
    bm.from_mesh(mesh)
    bm.transform(evaluated.matrix_world)
    volume = bm.calc_volume(signed=True)
    lo = [min(v.co[i] for v in bm.verts) for i in range(3)]
    hi = [max(v.co[i] for v in bm.verts) for i in range(3)]
    bm.free()
    evaluated.to_mesh_clear()
    want, want_lo, want_hi = obj_volume_and_bounds(w["obj"])
    volume_error = abs(volume - want) / abs(want)
    bounds_error = max(max(abs(a - b) for a, b in zip(lo, want_lo)), max(abs(a - b) for a, b in zip(hi, want_hi)))
    if volume_error > float(w.get("volume_tolerance", 1e-3)) or bounds_error > float(w.get("bounds_tolerance", 1e-4)):
        fail(f"frame {frame}: the surface holds {volume:.6g} m^3 in {lo}..{hi}; bw-export's mesh {want:.6g} m^3 in "
             f"{want_lo}..{want_hi}")
    report.append(f"water@{frame} {volume:.4g} m^3 (mesh {want:.4g}, bounds error {bounds_error:.2g} m)")

print("blender-scene-check: ok " + "; ".join(report))
