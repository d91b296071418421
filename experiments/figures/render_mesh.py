#!/usr/bin/python3
"""Render the boundary faces of a dtwire VTU preview (`dtwire mesh ... --vtu`) to a PNG.

Usage: render_mesh.py MESH.vtu OUT.png [--title TEXT] [--zoom X Y Z HALF]
--zoom adds a close-up panel: a cube of half-width HALF (mm) centred at (X, Y, Z);
--section ID adds the faces with boundary id ID (e.g. 1: wire A start face) in their plane.
Faces are coloured by boundary id (lateral surfaces, grips, end faces) and lit by their
normal, so the helix, the bends and the arms can be checked by eye.
"""
import argparse
import xml.etree.ElementTree as ET

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection


def read_array(piece, path, name=None):
    for array in piece.iter("DataArray"):
        if name is None or array.get("Name") == name:
            return np.array(array.text.split(), dtype=float)
    raise KeyError(name)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("vtu")
    parser.add_argument("png")
    parser.add_argument("--title", default="")
    parser.add_argument("--zoom", type=float, nargs=4, default=None)
    parser.add_argument("--section", type=int, default=None)
    args = parser.parse_args()
    piece = ET.parse(args.vtu).getroot().find("UnstructuredGrid/Piece")
    points = read_array(piece.find("Points"), "Points").reshape(-1, 3) * 1e3  # mm
    connectivity = read_array(piece, None, "connectivity").astype(int)
    offsets = read_array(piece, None, "offsets").astype(int)
    types = read_array(piece, None, "types").astype(int)
    region = read_array(piece, None, "region_id").astype(int)
    starts = np.concatenate([[0], offsets[:-1]])
    quads = [connectivity[s:e] for s, e, t in zip(starts, offsets, types) if t == 9]
    ids = region[types == 9]
    faces = points[np.array(quads)]
    palette = {0: (0.75, 0.55, 0.2), 1: (0.85, 0.3, 0.2), 2: (0.35, 0.55, 0.85), 3: (0.2, 0.7, 0.3), 4: (0.2, 0.7, 0.3)}
    base = np.array([palette[(i - 1) % 10] if (i - 1) // 10 == 0 else
                     tuple(0.6 * c + 0.1 for c in palette[(i - 1) % 10]) if (i - 1) % 10 != 2 else (0.85, 0.65, 0.3)
                     for i in ids])
    normals = np.cross(faces[:, 1] - faces[:, 0], faces[:, 3] - faces[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None] + 1e-30
    light = np.array([0.4, -0.8, 0.45])
    light /= np.linalg.norm(light)
    shade = 0.35 + 0.65 * np.abs(normals @ light)
    colours = np.clip(base * shade[:, None], 0, 1)

    panels = [(points.min(axis=0), points.max(axis=0), args.title, (12, -70))]
    if args.zoom:
        x, y, z, half = args.zoom
        centre = np.array([x, y, z])
        panels.append((centre - half, centre + half, f"close-up: faces inside a {2 * half:g} mm cube", (20, -35)))
    columns = len(panels) + (1 if args.section is not None else 0)
    fig = plt.figure(figsize=(9 * columns, 8), dpi=110)
    for index, (lo, hi, title, view) in enumerate(panels):
        ax = fig.add_subplot(1, columns, index + 1, projection="3d")
        keep = np.all((faces.min(axis=1) >= lo - 1e-9) & (faces.max(axis=1) <= hi + 1e-9), axis=1)
        edge_alpha = 0.15 if index == 0 else 0.6
        ax.add_collection3d(Poly3DCollection(faces[keep], facecolors=colours[keep],
                                             edgecolors=(0, 0, 0, edge_alpha), linewidths=0.2 if index == 0 else 0.4))
        centre, half = (lo + hi) / 2, (hi - lo).max() / 2
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(centre[2] - half, centre[2] + half)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=view[0], azim=view[1])
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_zlabel("z (mm)")
        ax.set_title(title)
    if args.section is not None:
        # The section faces in their own plane (principal axes of their nodes).
        section = faces[ids == args.section]
        flat = section.reshape(-1, 3)
        centre = flat.mean(axis=0)
        _, _, axes = np.linalg.svd(flat - centre)
        uv = (section - centre) @ axes[:2].T
        ax = fig.add_subplot(1, columns, columns)
        from matplotlib.collections import PolyCollection
        ax.add_collection(PolyCollection(uv, facecolors=(0.55, 0.75, 0.95), edgecolors="k", linewidths=0.6))
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_xlabel("u (mm)")
        ax.set_ylabel("v (mm)")
        ax.set_title(f"cross-section: boundary id {args.section} ({len(section)} quads)")
    fig.tight_layout()
    fig.savefig(args.png)


if __name__ == "__main__":
    main()
