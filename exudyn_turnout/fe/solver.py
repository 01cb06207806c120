"""Frequency-domain solution of Z(omega) q = f by exact condensation onto fewer DOFs.

Keep a small set of DOFs: the rail DOFs above the sleepers (where the pads are), every
DOF of the sleepers' element end nodes, and any DOF a load or a response needs. Every
other DOF then belongs to a small block that touches the rest only through kept DOFs:
the rail between two sleepers (its element interiors and mid-bay nodes), the interior
nodes of a sleeper element. The blocks are eliminated exactly at each frequency (Schur
complement)::

    S(omega) = Z_kk - sum_blocks Z_kb Z_bb^-1 Z_bk

and S (~5900 DOFs instead of ~34700 for the vertical turnout model) is factorised by
sparse LU (SuperLU). Three kinds of block:

- modal: no viscous damping inside and a structural loss proportional to the stiffness,
  Z_bb = (1 + i eta) K_bb - omega^2 M_bb (a rail bay). The eigenvectors Phi of
  (K_bb, M_bb), computed once, diagonalise it for every omega:
  Z_bb^-1 = Phi diag(1 / ((1 + i eta) lambda - omega^2)) Phi^T, so a frequency costs a
  few small products, no factorisation;
- damped modal: viscous damping inside (a sleeper element on its damped ballast):
  the 2 m_b complex modes lambda_r, v_r of the quadratic eigenproblem
  (lambda^2 M + lambda D + A) v = 0, computed once, give
  Z_bb(i omega)^-1 = sum_r v_r v_r^T / (c_r (i omega - lambda_r)),
  c_r = v_r^T (2 lambda_r M + D) v_r; each block is checked against a direct solve at
  setup and falls back to
- dense: batched dense solves at every frequency.

Nothing is approximated: the result equals the direct solve of the full system to
round-off (the tests check it). The blocks are found generically as connected
components of the matrix graph without the kept DOFs, so any kept set works.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla
from scipy.sparse.csgraph import connected_components

from exudyn_turnout.fe.model import PlaneModel

__all__ = [
    "DenseGroup",
    "ModalGroup",
    "DampedModalGroup",
    "CondensedSystem",
    "default_keep",
    "condense",
    "solve_full",
]

#: SuperLU with its default COLAMD ordering and partial pivoting. (SymmetricMode with a
#: small pivot threshold is faster on the full matrix but returned wrong results near
#: 2 kHz: relative residual 4. Every solve checks its residual.)
_LU_OPTIONS = dict(permc_spec="COLAMD")
_RESIDUAL_TOL = 1e-8


def _z(X: dict, omega: float):
    """A + i omega D - omega^2 M with A = K + iG (complex) from a dict of arrays."""
    return X["A"] + 1j * omega * X["D"] - omega**2 * X["M"]


@dataclass(frozen=True)
class DenseGroup:
    """Eliminated blocks of one size: m_b block DOFs, m_k kept DOFs they touch."""

    Xbb: dict  #: "A" = K + iG, "D", "M" -> (n, m_b, m_b)
    Xbk: dict  #: "A", "D", "M" -> (n, m_b, m_k)
    pos: np.ndarray  #: (n, m_k, m_k) positions of the Schur terms in the kept data array

    def schur_terms(self, omega: float) -> np.ndarray:
        """Z_kb Z_bb^-1 Z_bk of every block: what its elimination subtracts from Z_kk.

        Parameters
        ----------
        omega : float
            Circular frequency (rad/s).

        Returns
        -------
        numpy.ndarray
            Complex Schur terms (N/m), shape (n, m_k, m_k).
        """
        Zbk = _z(self.Xbk, omega)
        return np.swapaxes(Zbk, 1, 2) @ np.linalg.solve(_z(self.Xbb, omega), Zbk)


@dataclass(frozen=True)
class ModalGroup:
    """Blocks with Z_bb = (1 + i eta) K_bb - omega^2 M_bb, in the modal basis of K_bb, M_bb."""

    lam: np.ndarray  #: (n, m_b) eigenvalues lambda (rad^2/s^2)
    eta: np.ndarray  #: (n,) loss factor of each block
    Ybk: dict  #: "A", "D", "M" -> Phi^T X_bk, (n, m_b, m_k)
    pos: np.ndarray  #: (n, m_k, m_k) positions of the Schur terms in the kept data array

    def schur_terms(self, omega: float) -> np.ndarray:
        """Z_kb Z_bb^-1 Z_bk of every block: what its elimination subtracts from Z_kk.

        Parameters
        ----------
        omega : float
            Circular frequency (rad/s).

        Returns
        -------
        numpy.ndarray
            Complex Schur terms (N/m), shape (n, m_k, m_k).
        """
        Y = _z(self.Ybk, omega)
        modal_stiffness = (1.0 + 1j * self.eta)[:, None] * self.lam - omega**2
        return np.swapaxes(Y, 1, 2) @ (Y / modal_stiffness[:, :, None])


@dataclass(frozen=True)
class DampedModalGroup:
    """Blocks Z_bb = A + i omega D - omega^2 M in their complex (quadratic) modes."""

    lam: np.ndarray  #: (n, 2 m_b) eigenvalues lambda_r (1/s)
    c: np.ndarray  #: (n, 2 m_b) normalisation v_r^T (2 lambda_r M + D) v_r
    Ybk: dict  #: "A", "D", "M" -> V^T X_bk, (n, 2 m_b, m_k)
    pos: np.ndarray  #: (n, m_k, m_k)

    def schur_terms(self, omega: float) -> np.ndarray:
        """Z_kb Z_bb^-1 Z_bk of every block: what its elimination subtracts from Z_kk.

        Parameters
        ----------
        omega : float
            Circular frequency (rad/s).

        Returns
        -------
        numpy.ndarray
            Complex Schur terms (N/m), shape (n, m_k, m_k).
        """
        Y = _z(self.Ybk, omega)
        modal_stiffness = self.c * (1j * omega - self.lam)
        return np.swapaxes(Y, 1, 2) @ (Y / modal_stiffness[:, :, None])


@dataclass(frozen=True)
class CondensedSystem:
    """A plane model condensed onto the DOFs ``keep`` (see the module docstring)."""

    model: PlaneModel  #: the full model
    keep: np.ndarray  #: kept global DOFs, increasing
    data: dict  #: "A" = K + iG, "D", "M" -> data of Z_kk on the kept pattern
    indices: np.ndarray  #: CSC pattern of S (row indices)
    indptr: np.ndarray  #: CSC pattern of S (column pointers)
    groups: tuple[DenseGroup | ModalGroup | DampedModalGroup, ...]  #: the eliminated blocks

    @property
    def n_keep(self) -> int:
        """Number of kept DOFs, the size of S."""
        return len(self.keep)

    def schur(self, omega: float) -> sp.csc_matrix:
        """The condensed dynamic stiffness S(omega) on the kept DOFs.

        Parameters
        ----------
        omega : float
            Circular frequency (rad/s).

        Returns
        -------
        scipy.sparse.csc_matrix
            Complex S (N/m), n_keep x n_keep.
        """
        data = _z(self.data, omega)
        for group in self.groups:
            S = group.schur_terms(omega)
            flat = group.pos.ravel()
            data = data - (
                np.bincount(flat, S.real.ravel(), len(data))
                + 1j * np.bincount(flat, S.imag.ravel(), len(data))
            )
        n = self.n_keep
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(n, n))

    def factor(self, omega: float) -> sla.SuperLU:
        """Sparse LU factorisation of S(omega).

        Parameters
        ----------
        omega : float
            Circular frequency (rad/s).

        Returns
        -------
        scipy.sparse.linalg.SuperLU
            The factorisation; its ``.solve`` solves S X = B.
        """
        return sla.splu(self.schur(omega), **_LU_OPTIONS)

    def solve(self, omega: float, B: np.ndarray) -> np.ndarray:
        """X with S(omega) X = B on the kept DOFs, residual checked (two refinement steps).

        Parameters
        ----------
        omega : float
            Circular frequency (rad/s).
        B : numpy.ndarray
            Right-hand side(s) on the kept DOFs, (n_keep,) or (n_keep, m): forces (N).

        Returns
        -------
        numpy.ndarray
            Complex displacements X (m), of the shape of B.

        Raises
        ------
        RuntimeError
            The relative residual stays above 1e-8 (an ill-conditioned system).
        """
        S = self.schur(omega)
        lu = sla.splu(S, **_LU_OPTIONS)
        B = np.asarray(B, complex)
        X = _chunked(lu, B)
        for _ in range(2):
            R = B - S @ X
            if np.linalg.norm(R) <= _RESIDUAL_TOL * np.linalg.norm(B):
                return X
            X = X + _chunked(lu, R)
        raise RuntimeError(
            f"FE solve at {omega / (2 * np.pi):g} Hz: relative residual "
            f"{np.linalg.norm(R) / np.linalg.norm(B):.2g} after refinement"
        )

    def restrict(self, b: np.ndarray) -> np.ndarray:
        """Global vector(s) restricted to the kept DOFs.

        Parameters
        ----------
        b : numpy.ndarray
            Vector(s) over all DOFs of the model, (n_dof,) or (n_dof, m).

        Returns
        -------
        numpy.ndarray
            The rows of the kept DOFs, (n_keep,) or (n_keep, m).

        Raises
        ------
        ValueError
            b is non-zero on a condensed DOF.
        """
        b = np.asarray(b)
        mask = np.ones(b.shape[0], bool)
        mask[self.keep] = False
        if np.any(b[mask] != 0):
            raise ValueError(
                "the load / response vector touches DOFs that were condensed; keep them"
            )
        return b[self.keep]


def _blocks(pattern: sp.csr_matrix, keep: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Condensed DOFs and their component label (connected blocks without the kept DOFs)."""
    n = pattern.shape[0]
    condensed = np.setdiff1d(np.arange(n), keep)
    _, label = connected_components(pattern[condensed][:, condensed], directed=False)
    return condensed, label


def _kept_neighbours(
    pattern: sp.csr_matrix, members: np.ndarray, is_kept: np.ndarray
) -> np.ndarray:
    cols = pattern[members].indices
    return np.unique(cols[is_kept[cols]])


def default_keep(model: PlaneModel) -> np.ndarray:
    """Rail DOFs of the nodes above the sleepers and the sleepers' vertex DOFs.

    With rail torsion, also the torsion DOFs (phi, theta) of the nodes above the sleepers.

    Parameters
    ----------
    model : PlaneModel
        The model to condense.

    Returns
    -------
    numpy.ndarray
        Global DOF indices, increasing.
    """
    nodes = np.unique(model.mesh.pad_rail_node)
    vertex = model.vertex_dofs()
    sleepers = vertex[vertex >= model.sleeper_dof_offset]
    if model.torsion is not None:  # torsion DOFs of the pad nodes stay, those of the bays go
        sleepers = sleepers[sleepers < model.torsion_dof_offset]
        roll = model.roll_dof(nodes)
        torsion = [roll + j for j in range(model.torsion_dofs_per_node)]
    else:
        torsion = []
    return np.unique(np.concatenate([2 * nodes, 2 * nodes + 1, sleepers, *torsion]))


def condense(model: PlaneModel, keep: np.ndarray | None = None) -> CondensedSystem:
    """Prepare the exact condensation of ``model`` onto the DOFs ``keep``.

    Parameters
    ----------
    model : PlaneModel
        The full model of one plane.
    keep : array of int, optional
        Global DOFs to keep (loads and responses must lie on them); default
        :func:`default_keep`.

    Returns
    -------
    CondensedSystem
        The kept pattern and the eliminated blocks, ready for a solve at any frequency.
    """
    keep = np.unique(default_keep(model) if keep is None else np.asarray(keep, int))
    n = model.n_dof
    matrices = {k: getattr(model, k).tocsr() for k in "KGDM"}
    pattern = sp.csr_matrix(
        (np.ones(model.K.nnz), model.K.indices, model.K.indptr), shape=(n, n)
    ).T.tocsr()
    is_kept = np.zeros(n, bool)
    is_kept[keep] = True
    local = np.full(n, -1)
    local[keep] = np.arange(len(keep))
    condensed, label = _blocks(pattern, keep)
    order = np.argsort(label, kind="stable")
    bounds = np.searchsorted(label[order], np.arange(label.max() + 2))
    members = [condensed[order[bounds[i] : bounds[i + 1]]] for i in range(len(bounds) - 1)]
    touching = [local[_kept_neighbours(pattern, m, is_kept)] for m in members]
    kept = {k: matrices[k][keep][:, keep].tocoo() for k in "KGDM"}
    rows = np.concatenate([kept["K"].row] + [np.repeat(t, len(t)) for t in touching])
    cols = np.concatenate([kept["K"].col] + [np.tile(t, len(t)) for t in touching])
    linear, inverse = np.unique(cols.astype(np.int64) * len(keep) + rows, return_inverse=True)
    indices = (linear % len(keep)).astype(np.int32)
    indptr = np.searchsorted(linear // len(keep), np.arange(len(keep) + 1)).astype(np.int32)
    data = _combine({k: _on_pattern(kept[k], linear, len(keep)) for k in "KGDM"})
    groups = _groups(matrices, members, keep, touching, inverse[kept["K"].nnz :], len(linear))
    return CondensedSystem(model, keep, data, indices, indptr, groups)


def _chunked(lu, B: np.ndarray, chunk: int = 16) -> np.ndarray:
    """lu.solve on at most ``chunk`` right-hand sides at a time.

    SuperLU's solve time grows faster than linearly with their number: 432 at once took 30
    times longer.
    """
    if B.ndim == 1:
        return lu.solve(B)
    return np.column_stack(
        [lu.solve(np.ascontiguousarray(B[:, i : i + chunk])) for i in range(0, B.shape[1], chunk)]
    )


def _combine(X: dict) -> dict:
    """{"K", "G", "D", "M"} -> {"A" = K + iG, "D", "M"}."""
    return {"A": X["K"] + 1j * X["G"], "D": X["D"], "M": X["M"]}


def _on_pattern(coo: sp.coo_matrix, linear: np.ndarray, n: int) -> np.ndarray:
    pos = np.searchsorted(linear, coo.col.astype(np.int64) * n + coo.row)
    return np.bincount(pos, coo.data, len(linear))


def _groups(
    matrices, members, keep, touching, schur_pos, n_data
) -> tuple[DenseGroup | ModalGroup | DampedModalGroup, ...]:
    """Blocks of the eliminated components, batched by size and kind."""
    starts = np.cumsum([0] + [len(t) ** 2 for t in touching])
    by_size: dict[tuple[int, int], list[int]] = {}
    for i, (m, t) in enumerate(zip(members, touching)):
        by_size.setdefault((len(m), len(t)), []).append(i)
    groups: list[DenseGroup | ModalGroup | DampedModalGroup] = []
    for (_, mk), ids in by_size.items():
        rows = np.array([members[i] for i in ids])
        kcols = np.array([keep[touching[i]] for i in ids]).reshape(len(ids), mk)
        pos = np.array([schur_pos[starts[i] : starts[i + 1]] for i in ids]).reshape(
            len(ids), mk, mk
        )
        Xbb = {k: _dense(matrices[k], rows, rows) for k in "KGDM"}
        Xbk = _combine({k: _dense(matrices[k], rows, kcols) for k in "KGDM"})
        eta, modal = _proportional_loss(Xbb)
        if modal.any():
            groups.append(_modal_group(Xbb, Xbk, pos, eta, modal))
        rest = np.flatnonzero(~modal)
        if len(rest):
            damped, ok = _damped_modal_group(
                _combine({k: v[rest] for k, v in Xbb.items()}),
                {k: v[rest] for k, v in Xbk.items()},
                pos[rest],
            )
            if ok.any():
                groups.append(damped)
            if not ok.all():
                bad = rest[~ok]
                groups.append(
                    DenseGroup(
                        _combine({k: v[bad] for k, v in Xbb.items()}),
                        {k: v[bad] for k, v in Xbk.items()},
                        pos[bad],
                    )
                )
    return tuple(groups)


def _proportional_loss(Xbb: dict) -> tuple[np.ndarray, np.ndarray]:
    """Per block: eta with G_bb = eta K_bb, and whether that holds with D_bb = 0."""
    K, G, D = Xbb["K"], Xbb["G"], Xbb["D"]
    norm = np.einsum("nij,nij->n", K, K)
    eta = np.einsum("nij,nij->n", G, K) / norm
    off = np.einsum("nij,nij->n", G - eta[:, None, None] * K, G - eta[:, None, None] * K)
    modal = (off <= 1e-24 * norm) & (np.abs(D).reshape(len(D), -1).max(axis=1) == 0.0)
    return eta, modal


def _modal_group(
    Xbb: dict, Xbk: dict, pos: np.ndarray, eta: np.ndarray, sel: np.ndarray
) -> ModalGroup:
    """Eigenvectors Phi (Phi^T M Phi = I) of (K_bb, M_bb) and the projections Phi^T X_bk."""
    C = np.linalg.cholesky(Xbb["M"][sel])  # M = C C^T
    Ci = np.linalg.inv(C)
    lam, V = np.linalg.eigh(Ci @ Xbb["K"][sel] @ np.swapaxes(Ci, 1, 2))
    PhiT = np.swapaxes(V, 1, 2) @ Ci  # rows: M-orthonormal eigenvectors
    return ModalGroup(lam, eta[sel], {k: PhiT @ v[sel] for k, v in Xbk.items()}, pos[sel])


def _damped_modal_group(
    Zbb: dict, Ybk: dict, pos: np.ndarray
) -> tuple[DampedModalGroup, np.ndarray]:
    """Quadratic modes of every block and which blocks they reproduce.

    Checked at 0 and 1 kHz against direct solves to 1e-9; the group holds those blocks only.
    """
    A, D, M = Zbb["A"], Zbb["D"].astype(complex), Zbb["M"].astype(complex)
    n, m, _ = A.shape
    Minv = np.linalg.inv(M)
    L = np.zeros((n, 2 * m, 2 * m), complex)  # first-order form of (lam^2 M + lam D + A) v = 0
    L[:, :m, m:] = np.eye(m)
    L[:, m:, :m] = -Minv @ A
    L[:, m:, m:] = -Minv @ D
    lam, W = np.linalg.eig(L)
    V = W[:, :m, :]  # (n, m, 2m): v_r as columns
    c = _normalisation(V, lam, M, D)
    VT = np.swapaxes(V, 1, 2)
    group = DampedModalGroup(lam, c, {k: VT @ v for k, v in Ybk.items()}, pos)
    ok = np.ones(n, bool)
    for omega in (0.0, 2 * np.pi * 1000.0):
        Zbk = _z(Ybk, omega)
        direct = np.swapaxes(Zbk, 1, 2) @ np.linalg.solve(_z(Zbb, omega), Zbk)
        err = np.abs(group.schur_terms(omega) - direct).reshape(n, -1).max(axis=1)
        ok &= np.isfinite(err) & (err <= 1e-9 * np.abs(direct).reshape(n, -1).max(axis=1))
    sel = np.flatnonzero(ok)
    return DampedModalGroup(
        lam[sel], c[sel], {k: v[sel] for k, v in group.Ybk.items()}, pos[sel]
    ), ok


def _normalisation(V: np.ndarray, lam: np.ndarray, M: np.ndarray, D: np.ndarray) -> np.ndarray:
    """c_r = v_r^T (2 lambda_r M + D) v_r for the columns v_r of V, (n, 2m)."""
    MV, DV = M @ V, D @ V
    return np.einsum("nir,nir->nr", V, 2 * lam[:, None, :] * MV + DV)


def _dense(X: sp.csr_matrix, rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
    """Stacked dense submatrices X[rows[i]][:, cols[i]], shape (n, len(rows[i]), len(cols[i]))."""
    n, a = rows.shape
    b = cols.shape[1]
    sub = X[rows.ravel()].tocoo()  # row r belongs to block r // a, local row r % a
    blk = sub.row // a
    keys = (np.arange(n)[:, None] * X.shape[1] + cols).ravel()  # (block, column) -> local j
    order = np.argsort(keys)
    at = np.clip(
        np.searchsorted(keys[order], blk.astype(np.int64) * X.shape[1] + sub.col), 0, len(keys) - 1
    )
    hit = keys[order][at] == blk.astype(np.int64) * X.shape[1] + sub.col
    j = order[at] % b
    out = np.zeros((n, a, b))
    np.add.at(out, (blk[hit], sub.row[hit] % a, j[hit]), sub.data[hit])
    return out


def solve_full(model: PlaneModel, omega: float, B: np.ndarray) -> np.ndarray:
    """Direct sparse solve of the full system Z(omega) X = B (reference, slower).

    Parameters
    ----------
    model : PlaneModel
        The full model of one plane.
    omega : float
        Circular frequency (rad/s).
    B : numpy.ndarray
        Right-hand side(s) over all DOFs (N).

    Returns
    -------
    numpy.ndarray
        Complex displacements X (m), of the shape of B.
    """
    return sla.splu(model.dynamic_stiffness(omega), **_LU_OPTIONS).solve(np.asarray(B, complex))
