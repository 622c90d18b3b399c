"""The rectangular tube's finite-element J is solved with numpy alone (issue 42 item 6: scipy.sparse
took ~0.3 s to import for `gearhead solve beam`), and its rounding stays inside the accuracy it
states: checked against the same elimination carried out in extended precision."""

import subprocess
import sys

import numpy as np
import pytest

from gearhead.core import beams

LONG = np.longdouble


def test_tube_torsion_does_not_import_a_sparse_library():
    code = (
        "import sys\n"
        "from gearhead.core import beams\n"
        "beams.rectangular_tube_section(0.0508, 0.0254, 0.0015875)\n"
        "print(sorted(m for m in sys.modules if m.startswith('scipy')))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def _solve_long(A, B):
    """A·X = B in extended precision, A symmetric positive definite (batched): Gaussian elimination
    without pivoting, then back-substitution."""
    A, B = A.astype(LONG), B.astype(LONG)
    n = A.shape[-1]
    for k in range(n):
        f = A[..., k + 1 :, k] / A[..., k, k][..., None]
        A[..., k + 1 :, k:] -= f[..., :, None] * A[..., k, None, k:]
        B[..., k + 1 :, :] -= f[..., :, None] * B[..., k, None, :]
    X = np.zeros_like(B)
    for k in range(n - 1, -1, -1):
        rest = np.einsum("...j,...jm->...m", A[..., k, k + 1 :], X[..., k + 1 :, :])
        X[..., k, :] = (B[..., k, :] - rest) / A[..., k, k][..., None]
    return X


def _condensed_long(ratio, K1, M1, p, loads):
    """beams._condensed_elements in extended precision."""
    inner = np.arange(1, p)
    interior = (inner[:, None] * (p + 1) + inner[None, :]).ravel()
    edge = np.flatnonzero(~np.isin(np.arange((p + 1) ** 2), interior))
    a, b = np.kron(K1.astype(LONG), M1.astype(LONG)), np.kron(M1.astype(LONG), K1.astype(LONG))
    r = ratio.astype(LONG)[:, None, None]
    k = r * a + b / r
    k_ie, k_ee = k[:, interior][:, :, edge], k[:, edge][:, :, edge]
    rhs = np.concatenate([k_ie] + [f.astype(LONG)[:, interior, None] for f in loads], axis=2)
    x = _solve_long(k[:, interior][:, :, interior], rhs)
    out = [k_ee - np.einsum("eij,eik->ejk", k_ie, x[:, :, : len(edge)])]
    for n, f in enumerate(loads):
        z, f = x[:, :, len(edge) + n], f.astype(LONG)
        out.append((f[:, edge] - np.einsum("eij,ei->ej", k_ie, z), np.sum(f[:, interior] * z)))
    return (*out, edge)


def _energy_long(stiffness, loads, ld, extra, count, group):
    """f·K⁻¹f by beams._frontal_energy's assembly, one group at a time, in extended precision."""
    last = np.full(count, -1)
    for e in range(len(ld)):
        np.maximum.at(last, ld[e][ld[e] >= 0], group[e])
    extra = np.broadcast_to(np.asarray(extra, dtype=LONG), (count,))
    slot, front = np.full(count, -1), np.zeros(0, dtype=int)
    F, g, energy = np.zeros((0, 0), LONG), np.zeros(0, LONG), LONG(0)
    for gi in range(int(group.max()) + 1):
        els = np.flatnonzero(group == gi)
        new = np.array(sorted({int(d) for e in els for d in ld[e] if d >= 0 and slot[d] < 0}), dtype=int)
        n0, n = len(front), len(front) + len(new)
        slot[new], front = np.arange(n0, n), np.concatenate([front, new])
        grown = np.zeros((n, n), LONG)
        grown[:n0, :n0] = F
        F, g = grown, np.concatenate([g, extra[new]])
        for e in els:
            use = ld[e] >= 0
            at = slot[ld[e][use]]
            np.add.at(F, (at[:, None], at[None, :]), stiffness[e][np.ix_(use, use)].astype(LONG))
            np.add.at(g, at, loads[e][use].astype(LONG))
        done = last[front] == gi
        keep = ~done
        f_ek = F[np.ix_(done, keep)]
        z = _solve_long(F[np.ix_(done, done)], np.concatenate([f_ek, g[done][:, None]], axis=1))
        energy += g[done] @ z[:, -1]
        F, g = F[np.ix_(keep, keep)] - f_ek.T @ z[:, :-1], g[keep] - f_ek.T @ z[:, -1]
        slot[front[done]] = -1
        front = front[keep]
        slot[front] = np.arange(len(front))
    return energy


@pytest.mark.skipif(np.finfo(LONG).eps > 1e-18, reason="no extended precision on this platform")
@pytest.mark.parametrize("W,H", [(32.0, 16.0), (32.0, 32.0), (16.0, 16.0), (4.0, 4.0)])
def test_tube_bounds_carry_no_more_rounding_than_stated(W, H, monkeypatch):
    """The same mesh, element matrices and elimination order, carried out with a 64-bit mantissa
    (rounding 1e-19 instead of 1e-16): the J shown (the midpoint of the two bounds) is within
    beams.TUBE_ROUNDING of it. The scipy sparse LU this replaced was not: 2.1e-9 off on the 32×32
    (2×2×1/16 in) tube, its upper bound 4.3e-9 high."""
    lower, upper = beams._tube_torsion_bounds.__wrapped__(W, H)
    monkeypatch.setattr(beams, "_condensed_elements", _condensed_long)
    monkeypatch.setattr(beams, "_frontal_energy", _energy_long)
    lower_ref, upper_ref = beams._tube_torsion_bounds.__wrapped__(W, H)
    J, J_ref = (lower + upper) / 2, (lower_ref + upper_ref) / 2
    assert abs(float(J / J_ref - 1)) < beams.TUBE_ROUNDING
    assert abs(float(lower / lower_ref - 1)) < beams.TUBE_ROUNDING
    assert abs(float(upper / upper_ref - 1)) < 2 * beams.TUBE_ROUNDING


def test_a_tube_too_long_for_the_torsion_solve_is_refused_by_name():
    """A 1e9 in tall, 1 in wide tube met an exact zero pivot in the elimination ('could not be
    computed ... Singular matrix', no field named); past MAX_TUBE_ASPECT the longer side is named."""
    import pytest

    from gearhead.core import beams, model
    from gearhead.core.errors import InputError

    for name, other in (("height", "width"), ("width", "height")):
        with pytest.raises(InputError) as err:
            model.solve("beam", {name: "1e9"})
        assert err.value.field == name and other in err.value.message
    edge = model.solve(
        "beam", {"height": "1 in", "width": f"{1 / beams.MAX_TUBE_ASPECT!r} in", "wall": "1e-7 in"}
    )
    assert edge.outputs  # at the limit it still solves
