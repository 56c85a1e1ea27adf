"""The Mitsuba 3 half of tests/cli/mitsuba.rs: writes one closed Cornell box (an area light,
Lambertian walls, two Lambertian spheres) as a Glint scene (DIR/scene.toml) and as OBJ files,
renders it with Mitsuba 3's scalar_rgb path tracer (box pixel filter) and writes DIR/mitsuba.exr.
Usage: mitsuba_cornell.py DIR WIDTH SPP"""
import sys, os
out, W, SPP = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
# (material, 4 corners). Each quad is listed below wound outwards (counter-clockwise seen from
# outside the box); quad() reverses it, so that every face, and the light, faces into the box:
# front faces are the ones both renderers shade one-sidedly (Mitsuba) and emit from (both).
quads = []
def quad(mat, a, b, c, d): quads.append((mat, [a, d, c, b]))
# The box [-1, 1]^3, and a 0.6 x 0.6 light just under the ceiling.
quad("white", (-1,-1,-1), (1,-1,-1), (1,-1,1), (-1,-1,1))      # floor
quad("white", (-1,1,-1), (-1,1,1), (1,1,1), (1,1,-1))          # ceiling
quad("white", (-1,-1,1), (1,-1,1), (1,1,1), (-1,1,1))          # back wall z=+1
quad("white", (-1,-1,-1), (-1,1,-1), (1,1,-1), (1,-1,-1))      # front wall z=-1
quad("red",   (-1,-1,-1), (-1,-1,1), (-1,1,1), (-1,1,-1))      # left wall x=-1
quad("green", (1,-1,-1), (1,1,-1), (1,1,1), (1,-1,1))          # right wall x=+1
quad("lamp",  (-0.3,0.98,-0.3), (-0.3,0.98,0.3), (0.3,0.98,0.3), (0.3,0.98,-0.3))  # light
mats = {"white": (0.75, 0.75, 0.75), "red": (0.7, 0.1, 0.1), "green": (0.1, 0.6, 0.1), "lamp": (0.0, 0.0, 0.0)}
E = 12.0
spheres = [((-0.45, -0.6, 0.3), 0.4, "white"), ((0.45, -0.65, -0.2), 0.35, "white")]
cam = dict(pos=(0.0, 0.0, -0.95), look=(0.0, 0.0, 1.0), fov=70.0)
# Glint scene
t = [f"[render]\nwidth = {W}\nheight = {W}\nspp = {SPP}\nmax_depth = 64\n",
     f"[camera]\nposition = {list(cam['pos'])}\nlook_at = {list(cam['look'])}\nup = [0.0, 1.0, 0.0]\nfov_y = {cam['fov']}\n",
     "[world]\nambient = [0.0, 0.0, 0.0]\nbackground = [0.0, 0.0, 0.0]\n"]
for m, kd in mats.items():
    em = f"\nemission = [{E}, {E}, {E}]" if m == "lamp" else ""
    t.append(f"[materials.{m}]\nka = [0.0, 0.0, 0.0]\nkd = {list(kd)}\nks = [0.0, 0.0, 0.0]{em}\n")
for m in mats:
    vs = [v for (mm, q) in quads if mm == m for v in q]
    if not vs: continue
    tris = [[4*i, 4*i+1, 4*i+2] for i in range(len(vs)//4)] + [[4*i, 4*i+2, 4*i+3] for i in range(len(vs)//4)]
    t.append("[[objects]]\ntype = \"mesh\"\nvertices = [" + ", ".join(str([float(x) for x in v]) for v in vs) + "]\ntriangles = " + str(tris) + f"\nmaterial = \"{m}\"\n")
    with open(os.path.join(out, f"{m}.obj"), "w") as f:
        for v in vs: f.write("v %r %r %r\n" % tuple(float(x) for x in v))
        for a, b, c in tris: f.write(f"f {a+1} {b+1} {c+1}\n")
for c, r, m in spheres:
    t.append(f"[[objects]]\ntype = \"sphere\"\ncenter = {list(map(float, c))}\nradius = {r}\nmaterial = \"{m}\"\n")
open(os.path.join(out, "scene.toml"), "w").write("\n".join(t))
import mitsuba as mi
mi.set_variant("scalar_rgb")
d = {"type": "scene",
     "integrator": {"type": "path", "max_depth": 66},
     "sensor": {"type": "perspective", "fov": cam["fov"], "fov_axis": "y",
                "to_world": mi.ScalarTransform4f().look_at(origin=list(cam["pos"]), target=list(cam["look"]), up=[0, 1, 0]),
                "film": {"type": "hdrfilm", "width": W, "height": W, "rfilter": {"type": "box"}, "pixel_format": "rgb"},
                "sampler": {"type": "independent", "sample_count": SPP}}}
for m, kd in mats.items():
    s = {"type": "obj", "filename": os.path.join(out, f"{m}.obj"), "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": list(kd)}}, "face_normals": True}
    if m == "lamp":
        s["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": [E, E, E]}}
    d[m] = s
for i, (c, r, m) in enumerate(spheres):
    d[f"sphere{i}"] = {"type": "sphere", "center": list(c), "radius": r, "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": list(mats[m])}}}
scene = mi.load_dict(d)
import time
start = time.perf_counter()
img = mi.render(scene)
# For docs/performance.md's comparison of speed: the render alone, without loading.
print(f"mitsuba render: {time.perf_counter() - start:.3f} s, {W}x{W} at {SPP} spp")
mi.util.write_bitmap(os.path.join(out, "mitsuba.exr"), img)
