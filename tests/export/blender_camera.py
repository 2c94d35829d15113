# The camera check both Blender check scripts share (blender_check.py, blender_scene_check.py).
import math


def camera_view_error(scene, camera, view):
    """How far `camera` at view["frame"] is from the expected view: its place, view
    direction and up (largest coordinate difference), and its vertical field of view
    against view["fov_degrees"]; with what it has, for a message."""
    scene.frame_set(int(view["frame"]))
    m = camera.matrix_world
    # Blender's camera looks down its local -z with +y up, as glTF's.
    got = {"position": [m[r][3] for r in range(3)], "forward": [-m[r][2] for r in range(3)],
           "up": [m[r][1] for r in range(3)]}
    error = max(abs(got[k][r] - view[k][r]) for k in got for r in range(3))
    fov = math.degrees(camera.data.angle_y)
    return error, abs(fov - view["fov_degrees"]), f"{got}, fov {fov:.6g} degrees"


def camera_matches(error, fov_error):
    return error <= 1e-4 and fov_error <= 1e-3
