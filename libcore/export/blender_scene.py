# Sets up a Blender scene from the files bw-export wrote beside this script: the run's
# frame rate and frames, the solids and bodies of solids.glb with their animation and
# camera, the water as a surface (the VDB sequence through a Volume to Mesh modifier)
# with a water material in the colours of the scene's [render], the sun of [light],
# the sky, the image size of [render] and Cycles.
#
#   blender --python export/blender_scene.py                     # opens the run in Blender
#   blender -b --python export/blender_scene.py -- --save run.blend
#   blender -b --python export/blender_scene.py -o //images/ -a  # renders every frame
#
# From the command line it starts from an empty file (-- --keep: adds to the startup
# file instead); from Blender's text editor (Text > Open, Run Script) it adds to the
# file that is open. Everything goes into one collection, "breakwater", which a second
# run replaces. Blender frame F is the run's frame F. Written for Blender 3.4 and later.
#
# SETTINGS (above, written by bw-export) holds what the files alone do not say.
import glob
import math
import os
import re
import sys

import bpy
import mathutils

COLLECTION = "breakwater"


def script_folder():
    here = globals().get("__file__", "")
    if here and os.path.isfile(here):
        return os.path.dirname(os.path.abspath(here))
    # Run from the text editor, __file__ is the text's name: the text knows its file.
    space = getattr(bpy.context, "space_data", None)
    candidates = [getattr(bpy.context, "edit_text", None), getattr(space, "text", None)]
    candidates += [t for t in bpy.data.texts if t.name == os.path.basename(here)]
    for text in candidates:
        if text is not None and text.filepath and os.path.isfile(bpy.path.abspath(text.filepath)):
            return os.path.dirname(os.path.abspath(bpy.path.abspath(text.filepath)))
    raise RuntimeError("breakwater: cannot tell which folder this script is in: open it from the export folder "
                       "(Text > Open) before running it")


def from_command_line():
    # Run by --python: this file is among Blender's own arguments (those before --).
    here = globals().get("__file__", "")
    blender_args = sys.argv[:sys.argv.index("--")] if "--" in sys.argv else sys.argv
    return bool(here) and any(os.path.abspath(a) == os.path.abspath(here) for a in blender_args)


def script_arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    options = {"save": None, "keep": False}
    i = 0
    while i < len(argv):
        if argv[i] == "--save" and i + 1 < len(argv):
            options["save"] = argv[i + 1]
            i += 2
        elif argv[i] == "--keep":
            options["keep"] = True
            i += 1
        else:
            raise SystemExit(f"breakwater: unknown argument {argv[i]!r} (expected --save FILE.blend or --keep)")
    return options


def set_frame_rate(scene, rate):
    # Blender's rate is fps / fps_base: a whole number of frames per second exactly.
    if abs(rate - round(rate)) < 1e-9:
        scene.render.fps, scene.render.fps_base = int(round(rate)), 1.0
    else:
        scene.render.fps = int(math.ceil(rate))
        scene.render.fps_base = scene.render.fps / rate


def fresh_collection(scene):
    old = bpy.data.collections.get(COLLECTION)
    if old is not None:
        for obj in list(old.all_objects):
            bpy.data.objects.remove(obj, do_unlink=True)
        bpy.data.collections.remove(old)
    collection = bpy.data.collections.new(COLLECTION)
    scene.collection.children.link(collection)
    return collection


def move_to(collection, objects):
    for obj in objects:
        for other in list(obj.users_collection):
            other.objects.unlink(obj)
        collection.objects.link(obj)


def import_solids(folder, collection, scene):
    path = os.path.join(folder, "solids.glb")
    if not os.path.isfile(path):
        return None, None
    before = set(bpy.data.objects)
    # Shading "FLAT": the solids' faces are flat (and Debian 12's Blender 3.4 fails
    # with the importer's default "NORMALS").
    bpy.ops.import_scene.gltf(filepath=path, import_shading="FLAT")
    objects = [o for o in bpy.data.objects if o not in before]
    move_to(collection, objects)
    cameras = [o for o in objects if o.type == "CAMERA"]
    return objects, cameras[0] if cameras else None


def water_files(folder):
    files = {}
    for path in glob.glob(os.path.join(folder, "water_*.vdb")):
        m = re.fullmatch(r"water_(\d+)\.vdb", os.path.basename(path))
        if m:
            files[int(m.group(1))] = os.path.basename(path)
    return dict(sorted(files.items()))


def new_node_tree(owner, shader, output):
    """The owner's nodes, cleared, with a `shader` node linked into an `output` node."""
    owner.use_nodes = True
    nodes, links = owner.node_tree.nodes, owner.node_tree.links
    nodes.clear()
    node, out = nodes.new(shader), nodes.new(output)
    links.new(node.outputs[0], out.inputs[0])
    return node, out


def water_material():
    r = SETTINGS["render"]
    material = bpy.data.materials.new("breakwater water")
    bsdf, output = new_node_tree(material, "ShaderNodeBsdfPrincipled", "ShaderNodeOutputMaterial")
    nodes, links = material.node_tree.nodes, material.node_tree.links
    bsdf.inputs["Base Color"].default_value = (1, 1, 1, 1)
    bsdf.inputs["Roughness"].default_value = 0.02
    bsdf.inputs["IOR"].default_value = 1.333
    bsdf.inputs["Transmission"].default_value = 1.0
    # [render] absorption (per metre, per channel) as Beer-Lambert absorption inside:
    # Blender absorbs density x (1 - colour) per metre.
    absorption = r["absorption"]
    density = max(absorption)
    if density > 0:
        volume = nodes.new("ShaderNodeVolumeAbsorption")
        volume.inputs["Color"].default_value = (*[1 - a / density for a in absorption], 1)
        volume.inputs["Density"].default_value = density
        links.new(volume.outputs["Volume"], output.inputs["Volume"])
    material.diffuse_color = (*r["fluid_color"], 1)  # the viewport's solid colour
    return material


def import_water(folder, collection, scene):
    files = water_files(folder)
    if not files:
        return None, []
    if not bpy.app.build_options.openvdb or bpy.app.version < (2, 91, 0):
        raise RuntimeError(f"breakwater: this Blender ({bpy.app.version_string}) cannot read the water's OpenVDB files "
                           "into a surface (it needs OpenVDB and the Volume to Mesh modifier of Blender 2.91 or later); "
                           "export the water as meshes too (bw-export --mesh obj) and import those")
    numbers = list(files)
    bpy.ops.object.volume_import(filepath=os.path.join(folder, files[numbers[0]]), directory=folder,
                                 files=[{"name": name} for name in files.values()], use_sequence_detection=True)
    volume = bpy.context.active_object
    move_to(collection, [volume])
    volume.name = "water grids"
    grids = volume.data
    if len(numbers) > 1:
        # A sequence shows file number (frame - frame_start + 1 + frame_offset): so
        # Blender frame F shows water_F. Set here, since Blender detects no sequence
        # in numbers with gaps (--frames A:B:S); frames between show no water.
        grids.is_sequence = True
        grids.frame_start = numbers[0]
        grids.frame_offset = numbers[0] - 1
        grids.frame_duration = numbers[-1] - numbers[0] + 1
        grids.sequence_mode = "CLIP"
    if SETTINGS["up"] == "y":
        volume.rotation_euler = (math.pi / 2, 0, 0)  # bw-export --up y wrote (x, z, -y)
    # Blender's Volume to Mesh puts a grid's surface half a voxel further along each
    # axis than OpenVDB's own meshing does (Blender 3.4; also with the grids turned
    # by --up y): moved back by that half voxel, the surface is where bw-export's
    # --mesh puts it, around the particles (the tests compare the two).
    scene.frame_set(numbers[0])
    if not grids.grids.load():
        raise RuntimeError(f"breakwater: Blender cannot read {files[numbers[0]]}: {grids.grids.error_message}")
    index_to_object = next(g for g in grids.grids if g.name == "surface").matrix_object
    half_voxel = 0.5 * (index_to_object.to_3x3() @ mathutils.Vector((1, 1, 1)))
    volume.location = -half_voxel
    volume.hide_render = True
    volume.display_type = "BOUNDS"  # the surface below is what shows

    surface = bpy.data.objects.new("water", bpy.data.meshes.new("water"))
    collection.objects.link(surface)
    modifier = surface.modifiers.new("surface", "VOLUME_TO_MESH")
    modifier.object = volume
    modifier.grid_name = "surface"
    modifier.threshold = 0.0  # the level set's zero: the surface bw-export meshes
    modifier.resolution_mode = "GRID"
    modifier.adaptivity = 0.0
    modifier.use_smooth_shade = True
    surface.data.materials.append(water_material())
    return surface, numbers


def add_light_and_sky(collection, scene):
    light = SETTINGS["light"]
    sun = bpy.data.lights.new("breakwater sun", "SUN")
    sun.energy = 3.0 * light["intensity"]
    sun.color = light["color"]
    obj = bpy.data.objects.new("sun", sun)
    collection.objects.link(obj)
    # A sun shines down its local -z: turn -z into the direction the light travels.
    obj.rotation_euler = mathutils.Vector(light["direction"]).to_track_quat("-Z", "Y").to_euler()
    world = scene.world or bpy.data.worlds.new("breakwater sky")
    scene.world = world
    background, _ = new_node_tree(world, "ShaderNodeBackground", "ShaderNodeOutputWorld")
    background.inputs["Color"].default_value = (*SETTINGS["render"]["sky_color"], 1)
    background.inputs["Strength"].default_value = light["ambient"]


def cycles_can_denoise():
    # Builds without OpenImageDenoise (Debian's) fail to render with denoising on.
    try:
        import _cycles
        return bool(getattr(_cycles, "with_openimagedenoise", False))
    except ImportError:
        return False


def main():
    # From the text editor Blender's own arguments are not this script's.
    command_line = from_command_line()
    options = script_arguments() if command_line else {"save": None, "keep": True}
    folder = script_folder()
    if not options["keep"]:
        bpy.ops.wm.read_homefile(use_empty=True)
    scene = bpy.context.scene
    # The glTF importer turns seconds into frames at the scene's rate: set it first.
    set_frame_rate(scene, SETTINGS["frame_rate"])
    collection = fresh_collection(scene)
    solids, camera = import_solids(folder, collection, scene)
    surface, numbers = import_water(folder, collection, scene)
    add_light_and_sky(collection, scene)

    first, last = SETTINGS["frames"]
    if numbers:
        first, last = min(first, numbers[0]), max(last, numbers[-1])
        steps = {b - a for a, b in zip(numbers, numbers[1:])}
        scene.frame_step = steps.pop() if len(steps) == 1 else 1  # render the frames there are
    scene.frame_start, scene.frame_end = first, last
    scene.frame_set(first)
    if camera is not None:
        scene.camera = camera
    scene.render.resolution_x = SETTINGS["render"]["width"]
    scene.render.resolution_y = SETTINGS["render"]["height"]
    scene.render.resolution_percentage = 100
    scene.render.engine = "CYCLES"
    scene.cycles.samples = 128
    scene.cycles.use_denoising = cycles_can_denoise()

    if options["save"]:
        path = os.path.abspath(options["save"])
        bpy.ops.wm.save_as_mainfile(filepath=path)
        bpy.ops.file.make_paths_relative()  # the .blend finds the export where it lies beside it
        bpy.ops.wm.save_mainfile(filepath=path)
    print(f"breakwater: {f'{len(solids)} objects from solids.glb' if solids is not None else 'no solids.glb'}, "
          f"water in {len(numbers)} frames"
          f"{f' ({numbers[0]}..{numbers[-1]})' if numbers else ''}, frames {first}..{last} at "
          f"{SETTINGS['frame_rate']:g} fps, camera {'from solids.glb' if camera else 'none'}"
          f"{', saved ' + options['save'] if options['save'] else ''}")


main()
