# Renders a .glb written by `throng export --format gltf` in Blender, headless: imports it (Shading: Flat, which
# Debian 12's Blender 3.4 needs with NumPy 1.24), puts an orthographic camera above the agents at the chosen time,
# colours each agent's proxy by a per-object random hue, and renders one frame with Cycles on the CPU.
# Run through scripts/render-glb-screenshot (which gives the arguments after "--"):
#   blender -b --factory-startup --python scripts/render_glb_screenshot.py -- IN.glb OUT.png [TIME_S] [WIDTH HEIGHT]
import sys

import bpy
from mathutils import Vector

args = sys.argv[sys.argv.index("--") + 1:]
glb, png = args[0], args[1]
time_s = float(args[2]) if len(args) > 2 else 40.0
width, height = (int(args[3]), int(args[4])) if len(args) > 4 else (960, 540)

scene = bpy.context.scene
for o in list(bpy.data.objects):
    bpy.data.objects.remove(o, do_unlink=True)
bpy.ops.import_scene.gltf(filepath=glb, import_shading="FLAT")
agents = [o for o in scene.objects if o.name.startswith("agent_")]
if not agents:
    sys.exit("render_glb_screenshot: no agent_* nodes in " + glb)
frame = int(round(time_s * scene.render.fps / scene.render.fps_base)) + 1
scene.frame_set(frame)

# A material that gives every agent its own hue (Object Info › Random through a colour ramp).
material = bpy.data.materials.new("agent")
material.use_nodes = True
nodes, links = material.node_tree.nodes, material.node_tree.links
ramp = nodes.new("ShaderNodeValToRGB")
ramp.color_ramp.elements[0].color = (0.10, 0.35, 0.85, 1)
ramp.color_ramp.elements[1].color = (1.0, 0.55, 0.05, 1)
info = nodes.new("ShaderNodeObjectInfo")
links.new(info.outputs["Random"], ramp.inputs["Fac"])
links.new(ramp.outputs["Color"], nodes["Principled BSDF"].inputs["Base Color"])
for o in agents:
    o.data.materials.clear()
    o.active_material = material
# The proxy mesh (shared by every agent) with its faces' normals pointing outwards, so the tops catch the light.
import bmesh
for mesh in {o.data for o in agents}:
    bm = bmesh.new()
    bm.from_mesh(mesh)
    bmesh.ops.recalc_face_normals(bm, faces=bm.faces)
    bm.to_mesh(mesh)
    bm.free()

# The agents present at this frame (absent ones are scaled to zero) and their bounding box on the ground.
shown = [o for o in agents if o.matrix_world.to_scale().length > 1e-6]
points = [o.matrix_world.translation for o in shown] or [o.matrix_world.translation for o in agents]
lo = Vector((min(p.x for p in points), min(p.y for p in points), 0))
hi = Vector((max(p.x for p in points), max(p.y for p in points), 0))
centre = (lo + hi) / 2
span = max(hi.x - lo.x, (hi.y - lo.y) * width / height) + 2.0

bpy.ops.mesh.primitive_plane_add(size=1, location=(centre.x, centre.y, -0.01))
ground = bpy.context.object
ground.scale = (span * 2, span * 2, 1)
ground_material = bpy.data.materials.new("ground")
ground_material.use_nodes = True
# An even dark grey (emission: no sampling noise, which would make the PNG large), so the agents stand out.
ground_nodes = ground_material.node_tree.nodes
emission = ground_nodes.new("ShaderNodeEmission")
emission.inputs["Color"].default_value = (0.06, 0.065, 0.075, 1)
ground_material.node_tree.links.new(emission.outputs["Emission"], ground_nodes["Material Output"].inputs["Surface"])
ground.active_material = ground_material

camera_data = bpy.data.cameras.new("top")
camera_data.type = "ORTHO"
camera_data.ortho_scale = span
camera = bpy.data.objects.new("top", camera_data)
camera.location = (centre.x, centre.y, 100.0)
scene.collection.objects.link(camera)
scene.camera = camera

sun_data = bpy.data.lights.new("sun", type="SUN")
sun_data.energy = 4.0
sun = bpy.data.objects.new("sun", sun_data)
sun.rotation_euler = (0.35, 0.2, 0.8)  # nearly overhead: the tops of the arrowheads lit
scene.collection.objects.link(sun)
scene.world = scene.world or bpy.data.worlds.new("world")
scene.world.use_nodes = True
scene.world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.3

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = 64
try:  # a smooth picture compresses small; a Blender built without OpenImageDenoise renders with the noise
    scene.cycles.denoiser = "OPENIMAGEDENOISE"
    scene.cycles.use_denoising = True
except (TypeError, AttributeError):
    scene.cycles.use_denoising = False
scene.render.resolution_x, scene.render.resolution_y = width, height
scene.render.resolution_percentage = 100
scene.render.image_settings.file_format = "PNG"
scene.render.image_settings.color_mode = "RGB"
scene.render.image_settings.compression = 100
scene.render.filepath = png
bpy.ops.render.render(write_still=True)
print("render_glb_screenshot: %d agents (%d shown) at frame %d (%.1f s), wrote %s" % (len(agents), len(shown), frame, time_s, png))
