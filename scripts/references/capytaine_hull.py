"""Heave and pitch added mass A(omega) and damping B(omega) of a floating hull
by an independent boundary-element code, Capytaine 3 (M. Ancellin and
F. Dias, "Capytaine: a Python-based linear potential flow solver", J. Open
Source Softw. 4(36), 1341, 2019; https://capytaine.github.io), beside soak's
panel method for the same hull: the check behind the dynamics guide's
comparison of the built-in boat with an independent boundary-element code.

It reads the hull as soak floated it for its radiation bake (`soak
seakeeping MESH --hull-obj HULL.obj`: the mesh baked on, at its rest pose,
y up, still water at y = 0, centre of mass at x = z = 0) and the JSON of the
same run (`--json`), and solves the radiation of heave and pitch on deep
water at a few of soak's frequencies, spread over its sweep, and at
infinite frequency, with the fluid density and gravity soak used.

Frames: soak's (x, y, z), y up, becomes Capytaine's (X, Y, Z) = (x, -z, y),
Z up (a right-handed turn of 90 degrees about x; the still water plane is
Z = 0). Soak's heave (along y) is Capytaine's Heave; soak's pitch (about
z) is a rotation about -Y, i.e. minus Capytaine's Pitch, both about the
centre of mass (0, 0, center_of_mass_height). The sign cancels in the
diagonal terms compared here.

Capytaine gets the hull's immersed part (each triangle cut in four,
`--refine` times, before clipping: the same surface, finer panels; the
written hull's long thin triangles are far coarser than the panels soak cuts
them into) and a lid on the inner water plane (`generate_lid`) against
irregular frequencies. The immersed volume is checked against soak's
displaced volume (the script stops beyond 3 %: a hull or pose that is not
the one soak floated).

    cargo build --release -p soak-cli
    target/release/soak seakeeping builtin:boat --density 400 -r 64 --panels 240 \\
        --hull-obj boat.obj --json > boat.json
    python3 -m venv venv && venv/bin/pip install "capytaine>=3,<4"
    venv/bin/python scripts/references/capytaine_hull.py boat.obj boat.json [--count 8] [--refine 2]

prints, per mode, rows `omega, A soak, A Capytaine, ratio, B soak,
B Capytaine, ratio` (kg, kg/s for heave; kg m^2, kg m^2/s for pitch; the
ratios soak / Capytaine), then A-infinity. About a minute for the boat at
the default refinement (1,968 immersed faces and a 494-face lid).
"""

import argparse
import json
import sys

import numpy as np

# soak's JSON lists its six modes in this order: surge x, heave y, sway z,
# roll about x, yaw about y, pitch about z.
SOAK_MODE = {"heave": 1, "pitch": 5}
# Soak's mode -> (Capytaine's dof, sign of soak's motion in it).
CAPYTAINE_DOF = {"heave": ("Heave", 1.0), "pitch": ("Pitch", -1.0)}


def read_obj(path):
    """Vertices (n, 3) and triangles (m, 3, zero-based) of a Wavefront OBJ
    (faces of more than three vertices fanned into triangles)."""
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "v":
                vertices.append([float(w) for w in words[1:4]])
            elif words[0] == "f":
                corners = [int(w.split("/")[0]) for w in words[1:]]
                corners = [c - 1 if c > 0 else len(vertices) + c for c in corners]
                for k in range(1, len(corners) - 1):
                    faces.append([corners[0], corners[k], corners[k + 1]])
    return np.array(vertices, float), np.array(faces, int)


def refined(vertices, faces):
    """Each triangle cut in four at its edges' midpoints (shared midpoints
    shared), the surface unchanged."""
    vertices = list(map(tuple, vertices))
    middle = {}

    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in middle:
            middle[key] = len(vertices)
            vertices.append(tuple((np.array(vertices[a]) + np.array(vertices[b])) / 2))
        return middle[key]

    out = []
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    return np.array(vertices, float), np.array(out, int)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("obj", help="the hull at rest, from `soak seakeeping MESH --hull-obj FILE`")
    parser.add_argument("json", help="`soak seakeeping MESH --json` of the same run")
    parser.add_argument("--count", type=int, default=8, help="frequencies compared (default 8)")
    parser.add_argument("--refine", type=int, default=2, help="times each triangle is cut in four (default 2)")
    parser.add_argument("--no-lid", action="store_true", help="no lid against irregular frequencies")
    args = parser.parse_args()

    import capytaine as cpt

    cpt.set_logging(level="ERROR")  # not the mesh-resolution warnings: see --refine

    with open(args.json) as f:
        soak = json.load(f)
    rho = soak.get("water_density", 1000.0)
    g = soak.get("gravity", 9.80665)
    height = soak["center_of_mass_height"]
    rows = soak["rows"]

    vertices, faces = read_obj(args.obj)
    for _ in range(args.refine):
        vertices, faces = refined(vertices, faces)
    # soak (x, y, z), y up -> Capytaine (x, -z, y), z up.
    vertices = np.column_stack([vertices[:, 0], -vertices[:, 2], vertices[:, 1]])
    mesh = cpt.Mesh(vertices=vertices, faces=faces, name="hull")
    center = (0.0, 0.0, height)
    lid = None if args.no_lid else mesh.generate_lid(z=0.0)
    body = cpt.FloatingBody(
        mesh=mesh,
        lid_mesh=lid,
        dofs=cpt.rigid_body_dofs(only=["Heave", "Pitch"], rotation_center=center),
        center_of_mass=center,
    ).immersed_part()

    volume = body.disp_volume
    print(
        f"hull {args.obj}: {body.mesh.nb_faces} immersed faces"
        + ("" if body.lid_mesh is None else f", a lid of {body.lid_mesh.nb_faces}")
        + f"; immersed volume {volume:.5f} m^3, soak's {soak['displaced']:.5f} m^3"
        + f" ({100 * (volume / soak['displaced'] - 1):+.2f} %)"
    )
    print(f"soak: {soak['panels']} panels; rho = {rho} kg/m^3, g = {g} m/s^2, "
          f"centre of mass {height:+.4f} m above the water")
    if abs(volume / soak["displaced"] - 1) > 0.03:
        print("error: the immersed volume is not soak's: the hull or its pose is not the one soak floated",
              file=sys.stderr)
        sys.exit(1)

    picks = sorted(set(np.round(np.linspace(0, len(rows) - 1, args.count)).astype(int)))
    solver = cpt.BEMSolver()

    def solve(omega):
        out = {}
        for mode, (dof, _) in CAPYTAINE_DOF.items():
            problem = cpt.RadiationProblem(body=body, radiating_dof=dof, omega=omega, rho=rho, g=g)
            result = solver.solve(problem, keep_details=False)
            out[mode] = (result.added_mass[dof], result.radiation_damping[dof])
        return out

    solved = {k: solve(rows[k]["omega"]) for k in picks}
    ratios = {}
    for mode in CAPYTAINE_DOF:
        unit = ("kg", "kg/s") if mode == "heave" else ("kg m^2", "kg m^2/s")
        print()
        print(f"{mode} (A {unit[0]}, B {unit[1]}; ratio soak / Capytaine)")
        print(f"{'omega':>8} {'A soak':>10} {'A cpt':>10} {'ratio':>7} {'B soak':>10} {'B cpt':>10} {'ratio':>7}")
        ratios[mode] = []
        for k in picks:
            row = rows[k]
            omega = row["omega"]
            a, b = solved[k][mode]
            m = SOAK_MODE[mode]
            sa, sb = row["added_mass"][m], row["damping"][m]
            ratios[mode].append((sa / a, sb / b))
            print(f"{omega:8.3f} {sa:10.2f} {a:10.2f} {sa / a:7.3f} {sb:10.2f} {b:10.2f} {sb / b:7.3f}")

    infinite = solve(np.inf)
    print()
    print(f"{'A-infinity':>10} {'soak':>10} {'Capytaine':>10} {'ratio':>7}")
    for mode in CAPYTAINE_DOF:
        sa, a = soak["infinite"][SOAK_MODE[mode]], infinite[mode][0]
        print(f"{mode:>10} {sa:10.2f} {a:10.2f} {sa / a:7.3f}")
    print()
    for mode, r in ratios.items():
        r = np.array(r)
        print(f"{mode}: A ratio {r[:, 0].min():.3f}-{r[:, 0].max():.3f}, B ratio {r[:, 1].min():.3f}-{r[:, 1].max():.3f}")


if __name__ == "__main__":
    main()
