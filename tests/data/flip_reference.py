#!/usr/bin/env python3
"""LDR-FLIP (Andersson et al. 2020) written directly from the paper's description, with plain
2D convolutions and nothing from Twinlight: the values MetricsFlip.MatchesAnIndependent2D...
pins in tests/unit/test_metrics.cpp were printed by this script. Slow (pure Python); run it
only to re-derive them: python3 tests/data/flip_reference.py"""
import math

QC, QF, PC, PT, FEATURE_WIDTH = 0.7, 0.5, 0.4, 0.95, 0.082
CSF = {"A": (1.0, 0.0047, 0.0, 1e-5), "RG": (1.0, 0.0053, 0.0, 1e-5), "BY": (34.1, 0.04, 13.5, 0.025)}
XN, YN, ZN = 0.950428545, 1.0, 1.088900371
PPD = 67.0


def srgb_to_linear(v):
    v = min(max(v, 0.0), 1.0)
    return v / 12.92 if v <= 0.04045 else ((v + 0.055) / 1.055) ** 2.4


def rgb_to_xyz(r, g, b):
    return (0.4124 * r + 0.3576 * g + 0.1805 * b, 0.2126 * r + 0.7152 * g + 0.0722 * b,
            0.0193 * r + 0.1192 * g + 0.9505 * b)


def xyz_to_rgb(x, y, z):
    return (3.2406 * x - 1.5372 * y - 0.4986 * z, -0.9689 * x + 1.8758 * y + 0.0415 * z,
            0.0557 * x - 0.2040 * y + 1.0570 * z)


def xyz_to_ycxcz(x, y, z):
    return (116.0 * y / YN - 16.0, 500.0 * (x / XN - y / YN), 200.0 * (y / YN - z / ZN))


def ycxcz_to_xyz(yy, cx, cz):
    y = (yy + 16.0) / 116.0 * YN
    return ((cx / 500.0 + y / YN) * XN, y, (y / YN - cz / 200.0) * ZN)


def hunt_lab(r, g, b):
    x, y, z = rgb_to_xyz(r, g, b)
    f = lambda t: t ** (1.0 / 3.0) if t > 0.008856 else 7.787 * t + 16.0 / 116.0
    fx, fy, fz = f(x / XN), f(y / YN), f(z / ZN)
    l, a, bb = 116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)
    return (l, 0.01 * l * a, 0.01 * l * bb)


def hyab(p, q):
    return abs(p[0] - q[0]) + math.hypot(p[1] - q[1], p[2] - q[2])


def csf_kernel(a1, b1, a2, b2, radius):
    k = {}
    for y in range(-radius, radius + 1):
        for x in range(-radius, radius + 1):
            d2 = (x * x + y * y) / (PPD * PPD)
            k[(x, y)] = (a1 * math.sqrt(math.pi / b1) * math.exp(-math.pi ** 2 * d2 / b1) +
                         a2 * math.sqrt(math.pi / b2) * math.exp(-math.pi ** 2 * d2 / b2))
    s = sum(k.values())
    return {p: v / s for p, v in k.items()}


def feature_kernels():
    sigma = 0.5 * FEATURE_WIDTH * PPD
    radius = math.ceil(3.0 * sigma)
    edge, point = {}, {}
    for y in range(-radius, radius + 1):
        for x in range(-radius, radius + 1):
            g = math.exp(-(x * x + y * y) / (2.0 * sigma * sigma))
            edge[(x, y)] = -x * g
            point[(x, y)] = (x * x / (sigma * sigma) - 1.0) * g
    for k in (edge, point):
        pos = sum(v for v in k.values() if v > 0)
        neg = -sum(v for v in k.values() if v <= 0)
        for p in k:
            k[p] /= pos if k[p] > 0 else neg
    return edge, point, radius


def convolve(plane, w, h, kernel, radius):
    out = [0.0] * (w * h)
    for y in range(h):
        for x in range(w):
            s = 0.0
            for j in range(-radius, radius + 1):
                yy = min(max(y + j, 0), h - 1)
                for i in range(-radius, radius + 1):
                    s += kernel[(i, j)] * plane[yy * w + min(max(x + i, 0), w - 1)]
            out[y * w + x] = s
    return out


def flip(test, ref, w, h):
    max_b = max(max(c[1], c[3]) for c in CSF.values())
    radius = math.ceil(3.0 * math.sqrt(max_b / (2.0 * math.pi ** 2)) * PPD)
    kernels = [csf_kernel(*CSF[n], radius) for n in ("A", "RG", "BY")]
    edge, point, fr = feature_kernels()
    transposed = lambda k: {(y, x): v for (x, y), v in k.items()}

    def prepare(img):
        chans = [[0.0] * (w * h) for _ in range(3)]
        achromatic = [0.0] * (w * h)
        for i, (r, g, b) in enumerate(img):
            ycc = xyz_to_ycxcz(*rgb_to_xyz(srgb_to_linear(r), srgb_to_linear(g), srgb_to_linear(b)))
            for c in range(3):
                chans[c][i] = ycc[c]
            achromatic[i] = (ycc[0] + 16.0) / 116.0
        filtered = [convolve(chans[c], w, h, kernels[c], radius) for c in range(3)]
        feats = []
        for k in (edge, point):
            gx, gy = convolve(achromatic, w, h, k, fr), convolve(achromatic, w, h, transposed(k), fr)
            feats.append([math.hypot(a, b) for a, b in zip(gx, gy)])
        return filtered, feats

    (tf, (te, tp)), (rf, (re, rp)) = prepare(test), prepare(ref)
    cmax = hyab(hunt_lab(0, 1, 0), hunt_lab(0, 0, 1)) ** QC
    total = 0.0
    for i in range(w * h):
        def rgb(f):
            return [min(max(v, 0.0), 1.0) for v in xyz_to_rgb(*ycxcz_to_xyz(f[0][i], f[1][i], f[2][i]))]
        colour = hyab(hunt_lab(*rgb(tf)), hunt_lab(*rgb(rf))) ** QC
        colour = (PT / (PC * cmax) * colour if colour < PC * cmax
                  else PT + (colour - PC * cmax) / (cmax - PC * cmax) * (1.0 - PT))
        colour = min(max(colour, 0.0), 1.0)
        feature = (max(abs(re[i] - te[i]), abs(rp[i] - tp[i])) / math.sqrt(2.0)) ** QF
        total += colour ** (1.0 - min(max(feature, 0.0), 1.0))
    return total / (w * h)


def images(w, h):
    """The pair test_metrics.cpp builds: two colour halves against grey with a bright square."""
    test = [(0.9, 0.3, 0.2) if x < w // 2 else (0.2, 0.4, 0.8) for y in range(h) for x in range(w)]
    ref = [(0.95, 0.95, 0.9) if 8 <= x < 14 and 6 <= y < 12 else (0.5, 0.5, 0.5) for y in range(h) for x in range(w)]
    return test, ref


if __name__ == "__main__":
    w, h = 40, 24
    test, ref = images(w, h)
    print(f"split vs grey with a square, {w}x{h}, 67 ppd: {flip(test, ref, w, h):.10f}")
    uniform = lambda c: [c] * (w * h)
    print(f"uniform (0.8, 0.2, 0.2) vs (0.2, 0.2, 0.8): {flip(uniform((0.8, 0.2, 0.2)), uniform((0.2, 0.2, 0.8)), w, h):.10f}")
