#!/usr/bin/env python3
"""Reference values of the analytic ttest scenes in this folder, from closed forms only (no renderer).
Run: python3 references.py  (prints the value each XML file lists, with the formula)."""
import math

LUM = (0.212671, 0.715160, 0.072169)  # luminance weights of the ttest harness


def sub(a, b): return [x - y for x, y in zip(a, b)]
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def norm(a): return math.sqrt(dot(a, a))
def unit(a): return [x / norm(a) for x in a]


def projected_solid_angle(x, n, polygon):
    """Lambert (1760): the cosine-weighted solid angle of a polygon seen from x with normal n is
    1/2 |sum_i Theta_i (n . g_i)|, Theta_i the angle subtended by edge i, g_i the unit normal of the
    plane through x and that edge. The polygon must lie wholly above x's tangent plane."""
    total = 0.0
    for i in range(len(polygon)):
        a, b = unit(sub(polygon[i], x)), unit(sub(polygon[(i + 1) % len(polygon)], x))
        total += math.acos(max(-1.0, min(1.0, dot(a, b)))) * dot(n, unit(cross(a, b)))
    return 0.5 * abs(total)


def solid_angle(x, polygon):
    """Solid angle of a polygon (a fan from its first corner) seen from x, by Van Oosterom and
    Strackee (1983) per triangle: tan(Omega/2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)."""
    total = 0.0
    for i in range(1, len(polygon) - 1):
        a, b, c = sub(polygon[0], x), sub(polygon[i], x), sub(polygon[i + 1], x)
        la, lb, lc = norm(a), norm(b), norm(c)
        num = dot(a, cross(b, c))
        den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la
        total += 2.0 * math.atan2(num, den)
    return abs(total)


def fresnel(cos_i, eta_i, eta_t):
    """Unpolarised Fresnel reflectance of a smooth dielectric interface."""
    sin_t = eta_i / eta_t * math.sqrt(max(0.0, 1.0 - cos_i * cos_i))
    if sin_t >= 1.0:
        return 1.0
    cos_t = math.sqrt(1.0 - sin_t * sin_t)
    rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t)
    rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t)
    return 0.5 * (rs * rs + rp * rp)


def slab_transmittance(theta_deg, eta):
    """A parallel slab, light reflected any number of times inside (incoherently): the inner
    reflectance equals the outer one at the refracted angle (reciprocity), so
    T = (1 - R)^2 sum R^2k = (1 - R) / (1 + R). Radiance scaling eta^2 in and 1/eta^2 out cancel."""
    r = fresnel(math.cos(math.radians(theta_deg)), 1.0, eta)
    return (1.0 - r) / (1.0 + r)


def obj_polygon(path):
    """The vertices of a one-polygon OBJ file (its fan of triangles), in file order."""
    return [[float(t) for t in line.split()[1:4]] for line in open(path) if line.startswith("v ")]


if __name__ == "__main__":
    here = __file__.rsplit("/", 1)[0] if "/" in __file__ else "."
    print("furnace.xml: 1/(1-a) for a = 0.3, 0.7: %.7f %.7f; whitted 1 + a: 1.3 1.7" % (1 / 0.7, 1 / 0.3))
    print("furnace-far.xml: 1/(1-a) for a = 0.5: 2")
    x, n, albedo = [0, 0, 0], [0, 1, 0], 0.5
    for name in ["lshape", "triangle"]:
        phi = projected_solid_angle(x, n, obj_polygon(f"{here}/{name}.obj"))
        print(f"lambert.xml, {name}: projected solid angle {phi:.7f}; radiance (a/pi) phi = {albedo / math.pi * phi:.7f}")
        if name == "lshape":
            omega = solid_angle(x, obj_polygon(f"{here}/lshape.obj"))
            print(f"must_fail/lambert-cosine-dropped.xml: solid angle {omega:.7f}; (a/pi) omega = {albedo / math.pi * omega:.7f}")
    print("specular.xml, slab at normal incidence, eta 1.5: %.7f" % slab_transmittance(0.0, 1.5))
    print("specular.xml, slab at 45 degrees, eta 1.5: %.7f" % slab_transmittance(45.0, 1.5))
    # The mirror reflects the camera ray onto the origin: the floor point there is lit by lshape.obj.
    phi = projected_solid_angle(x, n, obj_polygon(f"{here}/lshape.obj"))
    print("specular.xml, mirror onto the floor lit by lshape.obj: %.7f" % (albedo / math.pi * phi))
