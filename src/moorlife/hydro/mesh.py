"""Hull geometry and panel mesh: the members of ``platform.yaml``, the wetted hull and the
interior lid as panels, and the Capytaine body (see :mod:`moorlife.hydro` for the frame)."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Member:
    """One cylindrical member of the hull.

    Attributes
    ----------
    name : str
    kind : str
        ``"column"`` (vertical, meshed with caps) or ``"brace"`` (tube joined to the columns it ends on).
    a, b : numpy.ndarray
        End points ``(3,)`` in m; for a column ``a`` is the bottom.
    diameter : float
        Outer diameter in m.
    cd : float
        Transverse (Morison) drag coefficient.
    axial_cd : float
        Axial drag coefficient applied over ``pi D^2 / 4`` at end ``a`` (heave plate); 0 if none.
    """

    name: str
    kind: str
    a: np.ndarray
    b: np.ndarray
    diameter: float
    cd: float
    axial_cd: float = 0.0

    @property
    def radius(self) -> float:
        return 0.5 * self.diameter

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.b - self.a))

    @property
    def axis(self) -> np.ndarray:
        return (self.b - self.a) / self.length


def members_from_config(platform_cfg: dict, source: str = "platform.yaml") -> list[Member]:
    """Build the member list from the ``members`` block of ``platform.yaml``.

    Raises
    ------
    ValueError
        Naming the file, the member and the field, on a missing or invalid value.
    """
    raw = platform_cfg.get("members")
    if not raw:
        raise ValueError(f"{source}: 'members' is missing or empty")
    out = []
    for i, m in enumerate(raw):
        where = f"{source}: members[{i}] ({m.get('name', '?')})"
        for key in ("name", "kind", "a", "b", "diameter", "cd"):
            if key not in m:
                raise ValueError(f"{where}: field '{key}' is missing")
        if m["kind"] not in ("column", "brace"):
            raise ValueError(f"{where}: kind = {m['kind']!r}, expected 'column' or 'brace'")
        a = np.asarray(m["a"], dtype=float)
        b = np.asarray(m["b"], dtype=float)
        if a.shape != (3,) or b.shape != (3,) or not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            raise ValueError(f"{where}: 'a' and 'b' must be 3 finite numbers, got {m['a']!r}, {m['b']!r}")
        if np.linalg.norm(b - a) <= 0:
            raise ValueError(f"{where}: a == b, the member has zero length")
        d = float(m["diameter"])
        if not d > 0:
            raise ValueError(f"{where}: diameter = {m['diameter']!r} must be > 0")
        cd = float(m["cd"])
        axcd = float(m.get("axial_cd", 0.0))
        if cd < 0 or axcd < 0:
            raise ValueError(f"{where}: drag coefficients must be >= 0, got cd={cd}, axial_cd={axcd}")
        if m["kind"] == "column":
            if not np.allclose(a[:2], b[:2]) or b[2] <= a[2]:
                raise ValueError(
                    f"{where}: a column must be vertical with a below b, got a={a.tolist()}, b={b.tolist()}"
                )
        out.append(Member(str(m["name"]), str(m["kind"]), a, b, d, cd, axcd))
    return out


def n_around(radius: float, panel_size: float, minimum: int = 8) -> int:
    """Number of panels around a circle of ``radius`` for a target panel size (even, >= minimum)."""
    n = max(minimum, int(np.ceil(2.0 * np.pi * radius / panel_size)))
    return n + (n % 2)


def _equal_area_radius(radius: float, n: int) -> float:
    # a regular n-gon of circumradius rho has area n rho^2 sin(2 pi / n) / 2
    return radius * np.sqrt(2.0 * np.pi / (n * np.sin(2.0 * np.pi / n)))


def _basis(e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    t = np.array([1.0, 0.0, 0.0]) if abs(e[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    if abs(e[2]) > 0.99:  # vertical: start the angle on +x so columns share orientation
        u = np.array([1.0, 0.0, 0.0])
    else:
        u = np.cross(e, t)
        u /= np.linalg.norm(u)
    v = np.cross(e, u)
    return u, v


def _start_basis(e: np.ndarray, start: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(u, v)`` with ``u`` along ``start`` made normal to ``e`` and ``v = e x u``."""
    u = start - (start @ e) * e
    u /= np.linalg.norm(u)
    return u, np.cross(e, u)


def wall_panels(
    a: np.ndarray,
    b: np.ndarray,
    radius: float,
    panel_size: float,
    n_theta: int | None = None,
    start: np.ndarray | None = None,
):
    """Quadrilateral panels of a cylinder wall from ``a`` to ``b`` (outward normals).

    ``start``: the direction of the first corner of every ring (made normal to the axis);
    None: ``+x`` for a vertical member, ``e x x`` or ``e x y`` otherwise.

    Returns
    -------
    vertices : numpy.ndarray
        ``(nv, 3)`` in m.
    faces : numpy.ndarray
        ``(nf, 4)`` vertex indices.
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    length = float(np.linalg.norm(b - a))
    e = (b - a) / length
    nt = n_theta or n_around(radius, panel_size)
    nz = max(1, int(np.ceil(length / panel_size)))
    rho = _equal_area_radius(radius, nt)
    u, v = _basis(e) if start is None else _start_basis(e, np.asarray(start, dtype=float))
    th = np.linspace(0.0, 2.0 * np.pi, nt + 1)[:-1]
    s = np.linspace(0.0, length, nz + 1)
    ring = rho * (np.cos(th)[:, None] * u + np.sin(th)[:, None] * v)
    vertices = (a + s[:, None, None] * e + ring[None, :, :]).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nz), np.arange(nt), indexing="ij")
    i, j = i.ravel(), j.ravel()
    jn = (j + 1) % nt
    # e_theta x e_s = +e_r (outward) for the order (j, s), (j+1, s), (j+1, s+1), (j, s+1)
    faces = np.stack([i * nt + j, i * nt + jn, (i + 1) * nt + jn, (i + 1) * nt + j], axis=1)
    return vertices, faces


def annulus_panels(
    centre,
    r_inner: float,
    r_outer: float,
    panel_size: float,
    normal_up: bool,
    n_theta: int | None = None,
    start_angle: float = 0.0,
):
    """Panels of a horizontal disk (``r_inner = 0``) or annulus at ``centre``.

    Returns ``(vertices (nv, 3), faces (nf, 4))``; triangles repeat their last vertex.
    The normal is ``+z`` if ``normal_up`` else ``-z``; the first corner of every ring is at
    ``start_angle`` (rad, from ``+x``).
    """
    c = np.asarray(centre, dtype=float)
    nt = n_theta or n_around(r_outer, panel_size)
    r_out = _equal_area_radius(r_outer, nt)
    # both rings carry nt corners at their own equal-area radius: the annulus has the exact
    # area pi (r_outer^2 - r_inner^2) (the inner ring of nt corners sits within 1 % of r_inner
    # of the narrower column's own polygon)
    r_in = _equal_area_radius(r_inner, nt) if r_inner > 0 else 0.0
    nr = max(1, int(np.ceil((r_out - r_in) / panel_size)))
    radii = np.linspace(r_in, r_out, nr + 1)
    th = start_angle + np.linspace(0.0, 2.0 * np.pi, nt + 1)[:-1]
    if r_in == 0.0:
        radii = radii[1:]
    ring = np.stack([np.cos(th), np.sin(th), np.zeros_like(th)], axis=1)
    vertices = (c + radii[:, None, None] * ring[None, :, :]).reshape(-1, 3)
    faces = []
    for i in range(len(radii) - 1):
        for j in range(nt):
            jn = (j + 1) % nt
            # r-hat x theta-hat = +z for (inner j, outer j, outer j+1, inner j+1)
            faces.append([i * nt + j, (i + 1) * nt + j, (i + 1) * nt + jn, i * nt + jn])
    if r_in == 0.0:
        ic = len(vertices)
        vertices = np.vstack([vertices, c[None, :]])
        for j in range(nt):
            faces.append([ic, j, (j + 1) % nt, (j + 1) % nt])
    faces = np.asarray(faces, dtype=int)
    if not normal_up:
        faces = faces[:, ::-1]
    return vertices, faces


def _clip_polygon_below(poly: list[np.ndarray], z: float) -> list[np.ndarray]:
    """The part of a planar polygon (list of ``(3,)`` corners) with ``z <= z``
    (Sutherland-Hodgman against one plane)."""
    out = []
    for p, q in zip(poly, poly[1:] + poly[:1]):
        p_in, q_in = p[2] <= z, q[2] <= z
        if p_in:
            out.append(p)
        if p_in != q_in:
            out.append(p + (z - p[2]) / (q[2] - p[2]) * (q - p))
    return out


def _clip_below(vertices: np.ndarray, faces: np.ndarray, z: float = 0.0):
    """Keep the part of every panel below ``z``.

    Panels entirely above are dropped; panels across ``z`` are cut along it (a cut quad is a
    triangle, a quad, or a pentagon stored as a quad and a triangle), so an inclined brace
    gets its exact elliptical waterline. Unused vertices are removed.
    """
    zf = vertices[faces, 2]
    below = np.all(zf <= z + 1e-9, axis=1)
    across = ~below & np.any(zf < z - 1e-9, axis=1)
    verts, new = [vertices], [faces[below]]
    n = len(vertices)
    for face in faces[across]:
        corners = list(dict.fromkeys(face.tolist()))  # a triangle repeats its last vertex
        poly = _clip_polygon_below([vertices[k] for k in corners], z)
        pieces = [[0, 1, 2, 3 if len(poly) > 3 else 2]] + ([[0, 3, 4, 4]] if len(poly) == 5 else [])
        verts.append(np.asarray(poly))
        new.append(n + np.asarray(pieces))
        n += len(poly)
    vertices, faces = np.vstack(verts), np.vstack(new)
    used, faces = np.unique(faces, return_inverse=True)
    return vertices[used], faces.reshape(-1, 4)


def _concat(parts):
    verts, faces, off = [], [], 0
    for v, f in parts:
        verts.append(v)
        faces.append(f + off)
        off += len(v)
    return np.vstack(verts), np.vstack(faces)


#: Minimum number of panels around a brace. A 1.6 m OC4 brace with 1.2 m panels would
#: otherwise be a hexagon; 12 lowered the surge added mass by 0.8 % (towards WAMIT) at the
#: default panel size, for 15 % more panels (validation/hydro.md).
BRACE_PANELS_AROUND = 12


def _inside_cylinder(points: np.ndarray, a: np.ndarray, b: np.ndarray, radius: float, tol: float = 1e-6) -> np.ndarray:
    """``(n,)`` True where ``points (n, 3)`` lie strictly inside the solid cylinder ``a -> b``."""
    length = float(np.linalg.norm(b - a))
    e = (b - a) / length
    s = (points - a) @ e
    d = np.linalg.norm(points - a - s[:, None] * e, axis=1)
    return (d < radius - tol) & (s > tol) & (s < length - tol)


def _drop_covered(
    vertices: np.ndarray, faces: np.ndarray, solids: Sequence[tuple[np.ndarray, np.ndarray, float, float]]
) -> np.ndarray:
    """``faces`` without the panels another member covers.

    ``solids`` holds cylinders ``(a, b, radius, margin)``. A panel is covered when its centre
    is inside one of them and every corner is inside the same one grown by ``margin`` (the
    smaller member's radius). The corner condition keeps panels much larger than the junction
    (coarse meshes): removing them would open a hole into the body, keeping them only leaves
    an overlap.
    """
    centres = vertices[faces].mean(axis=1)
    covered = np.zeros(len(faces), dtype=bool)
    for a, b, radius, margin in solids:
        covered |= _inside_cylinder(centres, a, b, radius) & _inside_cylinder(vertices, a, b, radius + margin)[
            faces
        ].all(axis=1)
    return faces[~covered]


def brace_extent(brace: Member, columns: Sequence[Member]) -> tuple[np.ndarray, np.ndarray, bool, bool]:
    """End points of a brace as meshed, and whether each end is closed by a column.

    An end that lies inside a column or on its wall (HydroDyn joints end on the wall) is
    pushed one column radius further along the brace axis, into the column, so that the
    brace and the column overlap; :func:`hull_panels` then removes the panels of each that lie
    inside the other (the union of the two solids). An end in open water is kept and gets a
    cap.

    Returns
    -------
    a, b : numpy.ndarray
        ``(3,)`` meshed end points, m.
    closed_a, closed_b : bool
        True where the end is inside a column.

    Raises
    ------
    ValueError
        Naming the brace and the column, if the pushed end leaves the column under water (a
        brace that grazes a column, or a column shorter than the push).
    """
    e = brace.axis
    out = []
    for end, sign in ((brace.a, -1.0), (brace.b, 1.0)):
        host = [c for c in columns if _inside_cylinder(end[None, :], c.a, c.b, c.radius, tol=-1e-3 * c.radius)[0]]
        if host:
            c = max(host, key=lambda c: c.radius)
            pushed = end + sign * c.radius * e
            if pushed[2] < 0.0 and not _inside_cylinder(pushed[None, :], c.a, c.b, c.radius)[0]:  # above: clipped
                raise ValueError(
                    f"brace {brace.name!r}: its end {end.round(3).tolist()} on column {c.name!r}, pushed "
                    f"{c.radius:g} m into the column along the brace, leaves it at "
                    f"{pushed.round(3).tolist()}: the mesher joins braces that enter a column "
                    "steeply enough to stay inside it for one column radius"
                )
            out.append((pushed, True))
        else:
            out.append((end, False))
    (a, closed_a), (b, closed_b) = out
    return a, b, closed_a, closed_b


def _disk_panels(centre: np.ndarray, normal: np.ndarray, radius: float, panel_size: float, n_theta: int):
    """A disk of ``radius`` at ``centre`` facing ``normal``, as ``(vertices, faces)``."""
    u, v = _basis(normal)
    verts, faces = annulus_panels([0.0, 0.0, 0.0], 0.0, radius, panel_size, True, n_theta)
    basis = np.stack([u, v, normal])  # local (x, y, z) -> (u, v, n): right-handed, keeps +z -> +n
    return centre + verts @ basis, faces


def _column_ring(m: Member, panel_size: float, around: float, mirror_planes: int) -> tuple[int, float]:
    """Panels around a column and the angle of its first corner (rad).

    With ``mirror_planes`` the layout follows the hull's mirror planes (:func:`hull_panels`):
    a column off the z axis starts on its radial line (a corner on each plane through its
    axis and the z axis), a column on the z axis gets a multiple of ``2 mirror_planes`` panels
    around (a corner on every plane)."""
    nt = n_around(m.radius, panel_size / around)
    if not mirror_planes:
        return nt, 0.0
    if np.hypot(m.a[0], m.a[1]) > 1e-9:
        return nt, float(np.arctan2(m.a[1], m.a[0]))
    k = 2 * int(mirror_planes)
    return -(-nt // k) * k, 0.0


def _onto_mirror_planes(members: Sequence[Member], mirror_planes: int, tol: float) -> list[Member]:
    """``members`` with every end point within ``tol`` of one of the ``mirror_planes`` vertical
    planes through the z axis (at ``k pi / mirror_planes``) moved onto it. The platform's
    coordinates are rounded (OC4: up to 2e-4 m off its planes); a member that far off a plane
    would leave sliver panels where the mesh is cut along the plane."""
    normals = [
        np.array([-np.sin(np.pi * k / mirror_planes), np.cos(np.pi * k / mirror_planes), 0.0])
        for k in range(mirror_planes)
    ]

    def onto(p: np.ndarray) -> np.ndarray:
        p = p.copy()
        for n in normals:
            d = float(p @ n)
            if abs(d) < tol:
                p -= d * n
        if np.hypot(p[0], p[1]) < tol:  # on two planes: on the axis
            p[:2] = 0.0
        return p

    return [dataclasses.replace(m, a=onto(m.a), b=onto(m.b)) for m in members]


def hull_panels(members: Sequence[Member], panel_size: float, around: float = 1.0, mirror_planes: int = 0):
    """Panels of the wetted hull (below z = 0) of a platform.

    Columns are closed by their end caps (an annulus where a narrower coaxial column
    continues). Braces are tubes pushed into the columns they end on (:func:`brace_extent`);
    the panels of a brace inside a column and those of a column inside a brace are removed,
    so that the mesh is the outer surface of the union of the members, with no enclosed
    fluid and no surface inside the body. A brace end in open water is capped.

    Parameters
    ----------
    members : sequence of Member
    panel_size : float
        Target panel edge length in m.
    around : float
        Circumferential refinement: every member gets ``around`` times as many panels around
        as ``panel_size`` gives (panels ``panel_size / around`` wide, ``panel_size`` long).
        The surge added mass converges with the number of panels around, not along
        (``validation/hydro.md``, section 0b).
    mirror_planes : int
        0: the layout of before (every ring starts on ``+x`` or a fixed axis). ``n > 0``: a
        layout that follows a hull with ``n`` vertical mirror planes through the z axis (at
        ``k pi / n``; OC4: 3), so that cutting the mesh along them cuts few panels and leaves
        no slivers (:func:`capytaine_body` with ``mirror_symmetry``): member end points within
        ``1e-3 panel_size`` of a plane are moved onto it, columns start on their radial line
        (:func:`_column_ring`), braces on the horizontal normal to their axis (a rule that
        commutes with rotations and with mirrors about vertical planes).

    Returns
    -------
    vertices : numpy.ndarray ``(nv, 3)``, faces : numpy.ndarray ``(nf, 4)``
    """
    if not panel_size > 0:
        raise ValueError(f"panel_size must be > 0, got {panel_size!r}")
    if not around > 0:
        raise ValueError(f"around must be > 0, got {around!r}")
    if mirror_planes:
        members = _onto_mirror_planes(members, int(mirror_planes), 1e-3 * panel_size)
    cols = [m for m in members if m.kind == "column"]
    braces = [(m, *brace_extent(m, cols)) for m in members if m.kind == "brace" and min(m.a[2], m.b[2]) < 0.0]
    parts = []
    brace_solids = [(a, b, br.radius, br.radius) for br, a, b, _, _ in braces]
    for m in cols:
        if m.a[2] >= 0.0:
            continue
        top = min(m.b[2], 0.0)
        nt, th0 = _column_ring(m, panel_size, around, mirror_planes)
        start = np.array([np.cos(th0), np.sin(th0), 0.0]) if mirror_planes else None
        col_parts = [wall_panels(m.a, np.array([m.a[0], m.a[1], top]), m.radius, panel_size, nt, start)]
        for end, up in ((m.a, False), (m.b, True)):
            if end[2] >= 0.0:
                continue
            # coaxial column continuing from this end on the other side
            others = [
                o
                for o in cols
                if o is not m and np.allclose(o.a[:2], m.a[:2]) and np.isclose((o.a if up else o.b)[2], end[2])
            ]
            r_cover = max((o.radius for o in others), default=0.0)
            if r_cover >= m.radius:
                continue
            col_parts.append(annulus_panels(end, r_cover, m.radius, panel_size, up, nt, th0))
        parts += [(v, _drop_covered(v, f, brace_solids)) for v, f in col_parts]
    for m, a, b, closed_a, closed_b in braces:
        nt = n_around(m.radius, panel_size / around, minimum=BRACE_PANELS_AROUND)
        caps = [
            _disk_panels(p, s * m.axis, m.radius, panel_size, nt)
            for p, s, closed in ((a, -1.0, closed_a), (b, 1.0, closed_b))
            if not closed and p[2] < 0.0
        ]
        column_solids = [(col.a, col.b, col.radius, m.radius) for col in cols]
        start = None
        if mirror_planes:  # horizontal, normal to the axis; radial for a vertical brace
            h = np.cross(m.axis, [0.0, 0.0, 1.0])
            start = (
                h if np.linalg.norm(h) > 1e-6 else np.array([*(a[:2] if np.hypot(*a[:2]) > 1e-9 else [1.0, 0.0]), 0.0])
            )
        parts += [
            _clip_below(v, _drop_covered(v, f, column_solids))
            for v, f in [wall_panels(a, b, m.radius, panel_size, nt, start), *caps]
        ]
    if not parts:
        raise ValueError("no member is below the still-water line: nothing to mesh")
    return _concat(parts)


def lid_panels(
    members: Sequence[Member], panel_size: float, z: float = 0.0, around: float = 1.0, mirror_planes: int = 0
):
    """Panels of the interior free surface (lid) of every column crossing the water line.

    ``around`` and ``mirror_planes`` as in :func:`hull_panels`, so that the lid rim matches
    the column polygon.

    Used for irregular-frequency removal. Braces are not lidded (their waterplane is < 2 %).
    Returns ``(vertices (nv, 3), faces (nf, 4))`` with normals pointing down (into the body).
    """
    if mirror_planes:
        members = _onto_mirror_planes(members, int(mirror_planes), 1e-3 * panel_size)
    parts = [
        annulus_panels(
            [m.a[0], m.a[1], z], 0.0, m.radius, panel_size, False, *_column_ring(m, panel_size, around, mirror_planes)
        )
        for m in members
        if m.kind == "column" and m.a[2] < z < m.b[2]
    ]
    if not parts:
        raise ValueError("no column crosses the water line: no lid to build")
    return _concat(parts)


def _to_mesh(vertices, faces, name):
    from capytaine import Mesh

    faces_list = [list(f[:3]) if f[2] == f[3] else list(f) for f in faces]
    return Mesh(vertices, faces_list, name=name)


def capytaine_body(
    members: Sequence[Member],
    panel_size: float,
    *,
    rotational_symmetry: int | None = None,
    mirror_symmetry: bool = False,
    lid: bool = True,
    around: float = 1.0,
):
    """The wetted hull as a ``capytaine.FloatingBody`` with six rigid-body dofs about the origin.

    Parameters
    ----------
    members : sequence of Member
    panel_size : float
        Target panel size in m.
    rotational_symmetry : int or None
        ``n`` to solve with an n-fold symmetry about the z axis (3 for OC4: about 3x faster).
        The hull is meshed whole, one wedge is cut out and rotated; a hull that is not
        n-fold symmetric is refused.
    mirror_symmetry : bool
        Also use the mirror symmetry about the plane y = 0 (xOz). With ``rotational_symmetry``
        ``n`` the hull has the dihedral symmetry of order ``2 n`` (OC4: the three vertical planes
        through its columns): the sector ``0 <= theta <= 180 / n`` deg is cut out, mirrored into
        the wedge and the wedge rotated, and Capytaine evaluates the Green function on a
        ``2 n``-th of the panels (a third fewer evaluations than rotation alone, half for
        OC4). Without it, the half ``y >= 0`` is mirrored. A hull without the symmetry is
        refused.
    lid : bool
        Add an interior free-surface lid (irregular-frequency removal).
    around : float
        Circumferential refinement (:func:`hull_panels`).

    Raises
    ------
    ValueError
        If ``rotational_symmetry`` is requested for a hull that does not have it.
    """
    import capytaine as cpt

    n = int(rotational_symmetry) if rotational_symmetry else None
    planes = (n or 1) if mirror_symmetry else 0  # vertical mirror planes of the hull: D_n has n
    hull = _to_mesh(*hull_panels(members, panel_size, around, planes), name="hull")
    lid_mesh = (
        _to_mesh(*lid_panels(members, panel_size, around=around, mirror_planes=planes), name="lid") if lid else None
    )
    if n or mirror_symmetry:
        sym = _symmetric(hull, n, mirror_symmetry, "hull")
        ref, got = _mesh_moments(hull), _mesh_moments(sym)
        # the panels of the whole hull and of the one rebuilt from its symmetric part: a mirror
        # image in x, y alone is not told apart by the moments (a brace climbing one way)
        gap = _largest_gap(hull, sym) if mirror_symmetry else 0.0
        if not np.allclose(got, ref, rtol=0.0, atol=0.01 * abs(ref[0])) or gap > panel_size:
            what = " and ".join(
                ([f"{n}-fold symmetric about z"] if n else [])
                + (["mirror-symmetric about y = 0"] if mirror_symmetry else [])
            )
            raise ValueError(
                f"hydro.mesh.rotational_symmetry = {rotational_symmetry}, mirror_symmetry = {mirror_symmetry}: "
                f"the hull is not {what} (volume/first moments {ref.round(1).tolist()} whole vs "
                f"{got.round(1).tolist()} rebuilt from the symmetric part"
                + (f"; a panel {gap:.2g} m from any of the other" if mirror_symmetry else "")
                + "); set "
                + ("mirror_symmetry to false" if mirror_symmetry else "it to null")
            )
        hull = sym
        if lid_mesh is not None:
            lid_mesh = _symmetric(lid_mesh, n, mirror_symmetry, "lid")
    return cpt.FloatingBody(
        mesh=hull,
        lid_mesh=lid_mesh,
        dofs=cpt.rigid_body_dofs(rotation_center=(0.0, 0.0, 0.0)),
        center_of_mass=(0.0, 0.0, 0.0),
        name="platform",
    )


def _symmetric(mesh, n: int | None, mirror: bool, name: str):
    """``mesh`` as Capytaine's symmetric mesh: rotation (``n``), mirror about y = 0, or both."""
    import capytaine as cpt

    if n and mirror:  # dihedral: the sector 0 <= theta <= 180 / n deg, mirrored, rotated
        return cpt.RotationSymmetricMesh(
            cpt.ReflectionSymmetricMesh(mesh.extract_wedge(2 * n), plane="xOz"), n=n, name=name
        )
    if n:
        return cpt.RotationSymmetricMesh(mesh.extract_wedge(n), n=n, name=name)
    return cpt.ReflectionSymmetricMesh(
        mesh.clipped(origin=(0.0, 0.0, 0.0), normal=(0.0, -1.0, 0.0)), plane="xOz", name=name
    )


def _mesh_moments(mesh) -> np.ndarray:
    # volume (from x n_x) and the first moments of area of the panels: a symmetry fingerprint
    n, c, a = mesh.faces_normals, mesh.faces_centers, mesh.faces_areas
    return np.array([np.sum(c[:, 0] * n[:, 0] * a), np.sum(c[:, 0] * a), np.sum(c[:, 1] * a), np.sum(a)])


def _largest_gap(mesh, other) -> float:
    """The largest distance (m) from a panel centre of either mesh to the nearest of the other."""
    from scipy.spatial import cKDTree

    a, b = mesh.faces_centers, other.faces_centers
    return float(max(cKDTree(b).query(a)[0].max(), cKDTree(a).query(b)[0].max()))
