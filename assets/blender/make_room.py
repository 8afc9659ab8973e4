"""Builds a furnished room in Blender and exports it as binary glTF, for nullpath's
scenes/blender-room-black-hole.toml.

    blender -b --factory-startup --python assets/blender/make_room.py -- scenes/models/blender-room.glb

The room is nullpath's black-hole room, x in [-6, 6], y in [-4, 4] (up), z in [-8, 8] in glTF's
y-up frame (Blender works z-up: its (x, y, z) is glTF's (x, z, -y)), with the hole's centre at the
origin left clear: a table with four chairs, a bookcase with books, two floor lamps, a ceiling
light, a window with a glass pane in the back wall, a glass vase, a chrome ball and a brass bowl.
Chairs, table legs, books and lamps are linked duplicates (one mesh, many objects), which the
exporter writes as one glTF mesh placed by many nodes: nullpath instances them.
"""

import math
import sys

import bpy

OUT = sys.argv[sys.argv.index("--") + 1] if "--" in sys.argv else "blender-room.glb"

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def material(name, colour, metallic=0.0, roughness=0.5, transmission=0.0, ior=1.5, emission=None, strength=1.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Transmission"].default_value = transmission
    bsdf.inputs["IOR"].default_value = ior
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
        # Exported as doubleSided = false: emitters light their front side only (Blender's
        # default, no back-face culling, exports doubleSided = true, and the ceiling light would
        # also light the ceiling a centimetre above it).
        m.use_backface_culling = True
    return m


def finish(obj, name, mat):
    obj.name = name
    obj.data.name = name
    obj.data.materials.clear()
    obj.data.materials.append(mat)
    return obj


def box(name, centre, size, mat):
    """An axis-aligned box (Blender coordinates), its size baked into the mesh."""
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=centre)
    obj = bpy.context.object
    obj.scale = size
    bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)
    return finish(obj, name, mat)


def cylinder(name, centre, radius, depth, mat, vertices=32):
    bpy.ops.mesh.primitive_cylinder_add(vertices=vertices, radius=radius, depth=depth, location=centre)
    obj = bpy.context.object
    bpy.ops.object.shade_smooth()
    return finish(obj, name, mat)


def sphere(name, centre, radius, mat):
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=radius, location=centre)
    obj = bpy.context.object
    bpy.ops.object.shade_smooth()
    return finish(obj, name, mat)


def join(name, parts):
    """Joins parts (their materials kept per face) into one object."""
    bpy.ops.object.select_all(action="DESELECT")
    for p in parts:
        p.select_set(True)
    bpy.context.view_layer.objects.active = parts[0]
    bpy.ops.object.join()
    obj = bpy.context.object
    obj.name = name
    obj.data.name = name
    return obj


def place(original, name, location, rotation_z=0.0):
    """A linked duplicate: a new object sharing `original`'s mesh."""
    obj = bpy.data.objects.new(name, original.data)
    scene.collection.objects.link(obj)
    obj.location = location
    obj.rotation_euler = (0.0, 0.0, rotation_z)
    return obj


plaster = material("Plaster", (0.75, 0.73, 0.7), roughness=0.9)
blue_wall = material("BlueWall", (0.45, 0.55, 0.72), roughness=0.9)
floor_wood = material("FloorWood", (0.42, 0.27, 0.15), roughness=0.55)
oak = material("Oak", (0.6, 0.42, 0.25), roughness=0.45)
walnut = material("Walnut", (0.3, 0.18, 0.1), roughness=0.5)
chrome = material("Chrome", (0.95, 0.95, 0.95), metallic=1.0, roughness=0.0)
brass = material("Brass", (0.9, 0.7, 0.35), metallic=1.0, roughness=0.25)
steel = material("Steel", (0.6, 0.6, 0.62), metallic=1.0, roughness=0.4)
glass = material("Glass", (1.0, 1.0, 1.0), roughness=0.0, transmission=1.0, ior=1.5)
green_glass = material("GreenGlass", (0.7, 0.95, 0.8), roughness=0.0, transmission=1.0, ior=1.52)
ceiling_light = material("CeilingLight", (0.9, 0.9, 0.9), emission=(1.0, 0.95, 0.85), strength=6.0)
lamp_shade = material("LampShade", (0.9, 0.85, 0.7), emission=(1.0, 0.8, 0.55), strength=4.0)
book_colours = [(0.6, 0.1, 0.1), (0.1, 0.3, 0.55), (0.15, 0.45, 0.2), (0.75, 0.6, 0.2)]
books = [material(f"Book{i}", c, roughness=0.7) for i, c in enumerate(book_colours)]

# The room (Blender: x right, y back, z up): walls 0.2 thick outside the box x in [-6, 6],
# y in [-8, 8], z in [-4, 4]; the back wall (y = 8, glTF z = -8) has a window.
T = 0.2
box("Floor", (0, 0, -4 - T / 2), (12, 16, T), floor_wood)
box("Ceiling", (0, 0, 4 + T / 2), (12, 16, T), plaster)
box("LeftWall", (-6 - T / 2, 0, 0), (T, 16, 8), plaster)
box("RightWall", (6 + T / 2, 0, 0), (T, 16, 8), blue_wall)
box("FrontWall", (0, -8 - T / 2, 0), (12, T, 8), plaster)
# Back wall around a window x in [1.5, 4.5], z in [-1, 2].
box("BackWallLeft", (-2.25, 8 + T / 2, 0), (7.5, T, 8), plaster)
box("BackWallRight", (5.25, 8 + T / 2, 0), (1.5, T, 8), plaster)
box("BackWallBelow", (3, 8 + T / 2, -2.5), (3, T, 3), plaster)
box("BackWallAbove", (3, 8 + T / 2, 3), (3, T, 2), plaster)
box("WindowPane", (3, 8 + T / 2, 0.5), (3, 0.03, 3), glass)
box("WindowSill", (3, 8 - 0.1, -1.05), (3.3, 0.3, 0.1), oak)
# The ceiling light is one quad facing down: a thin emitting box would light the gap above it.
bpy.ops.mesh.primitive_plane_add(size=3.0, location=(0, 0, 3.99), rotation=(math.pi, 0, 0))
finish(bpy.context.object, "CeilingLight", ceiling_light)

# Table (top and four linked legs) at the left, with chairs around it.
TABLE = (-3.6, 2.5)
box("TableTop", (TABLE[0], TABLE[1], -2.55), (2.2, 1.4, 0.1), oak)
leg = box("TableLeg", (0, 0, 0), (0.1, 0.1, 1.4), walnut)
for i, (dx, dy) in enumerate([(-1, -0.6), (1, -0.6), (-1, 0.6), (1, 0.6)]):
    if i == 0:
        leg.location = (TABLE[0] + dx, TABLE[1] + dy, -3.3)
    else:
        place(leg, f"TableLeg.{i}", (TABLE[0] + dx, TABLE[1] + dy, -3.3))

seat = box("ChairSeat", (0, 0, -3.1), (0.55, 0.55, 0.06), oak)
back = box("ChairBack", (0, 0.25, -2.6), (0.55, 0.05, 0.9), oak)
legs = [box(f"ChairLeg{k}", (sx * 0.24, sy * 0.24, -3.55), (0.05, 0.05, 0.9), walnut)
        for k, (sx, sy) in enumerate([(-1, -1), (1, -1), (-1, 1), (1, 1)])]
chair = join("Chair", [seat, back] + legs)
CHAIR_Z = chair.location.z  # the joined object's origin is the seat's
for i, (x, y, angle) in enumerate([
    (TABLE[0], TABLE[1] - 1.1, math.pi), (TABLE[0], TABLE[1] + 1.1, 0.0),
    (TABLE[0] - 1.5, TABLE[1], math.pi / 2), (TABLE[0] + 1.5, TABLE[1], -math.pi / 2),
]):
    if i == 0:
        chair.location = (x, y, CHAIR_Z)
        chair.rotation_euler = (0, 0, angle)
    else:
        place(chair, f"Chair.{i}", (x, y, CHAIR_Z), angle)

# On the table: a glass vase, a brass bowl, a chrome ball.
cylinder("Vase", (TABLE[0] - 0.5, TABLE[1], -2.2), 0.15, 0.6, green_glass)
bowl = sphere("Bowl", (TABLE[0] + 0.4, TABLE[1] - 0.2, -2.4), 0.22, brass)
bowl.scale = (1, 1, 0.45)
sphere("ChromeBall", (TABLE[0] + 0.5, TABLE[1] + 0.35, -2.3), 0.2, chrome)

# A bookcase against the right wall, with rows of linked books.
CASE_X = 5.6
box("CaseSideNear", (CASE_X, -1.5, -2.0), (0.7, 0.05, 4), walnut)
box("CaseSideFar", (CASE_X, 1.5, -2.0), (0.7, 0.05, 4), walnut)
for k, z in enumerate([-3.95, -2.6, -1.3, 0.0]):
    box(f"Shelf{k}", (CASE_X, 0, z), (0.7, 3.0, 0.05), walnut)
book_meshes = [box(f"Book{i}", (0, 0, 0), (0.45, 0.12, 0.8 + 0.05 * i), books[i]) for i in range(4)]
count = 0
for k, z in enumerate([-3.95, -2.6, -1.3]):
    y = -1.35
    j = 0
    while y < 1.3:
        m = book_meshes[(j * 3 + k) % 4]
        height = m.dimensions.z
        if m.location.length == 0:
            m.location = (CASE_X, y, z + 0.025 + height / 2)
        else:
            place(m, f"{m.data.name}.{count}", (CASE_X, y, z + 0.025 + height / 2))
        count += 1
        y += 0.14
        j += 1

# Two floor lamps: a steel pole and base, an emitting shade.
pole = cylinder("LampPole", (0, 0, -2.5), 0.03, 3.0, steel, vertices=12)
base = cylinder("LampBase", (0, 0, -3.97), 0.25, 0.06, steel)
lamp = join("FloorLamp", [pole, base])
LAMP_Z = lamp.location.z  # the pole's
shade = cylinder("LampShade", (0, 0, -0.8), 0.3, 0.45, lamp_shade)
for i, (x, y) in enumerate([(-5.2, -5.5), (4.8, 5.5)]):
    if i == 0:
        lamp.location = (x, y, LAMP_Z)
        shade.location = (x, y, -0.8)
    else:
        place(lamp, "FloorLamp.1", (x, y, LAMP_Z))
        place(shade, "LampShade.1", (x, y, -0.8))

# A rug under the table.
box("Rug", (TABLE[0], TABLE[1], -3.995), (3.4, 2.8, 0.01), material("Rug", (0.5, 0.15, 0.12), roughness=1.0))

bpy.ops.export_scene.gltf(
    filepath=OUT,
    export_format="GLB",
    export_yup=True,
    export_apply=False,
    export_cameras=False,
    export_lights=False,
    export_texcoords=True,
    export_normals=True,
    export_materials="EXPORT",
)
print(f"wrote {OUT}")
