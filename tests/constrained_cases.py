"""Shared constrained cases: planar four-bar linkages and their energy-method closed forms (theory: constraints).

Geometry (plane x-z, joints about -y so that positive angles turn +x toward +z, complex
coordinates x + i z): ground pivots O2 = 0 and O4 = d; crank O2 -> A (length a, absolute
angle theta), coupler A -> B (b, phi), rocker B -> O4 (c, chi: the direction from B to
O4).  The URDF is the open chain crank -> coupler -> rocker; a point constraint closes
it at the rocker's tip.  Each link has mass m, its centre of mass s along the link from
its proximal joint, and in-plane inertia I about the centre of mass.

The loop equation a e^{i theta} + b e^{i phi} + c e^{i chi} = d and its first two
derivatives in theta give phi', chi', phi'', chi''; then, with v_k the centres of mass,

    M_eff = sum_k m_k |v_k'|^2 + I_k omega_k'^2,    V' = g sum_k m_k Im v_k',
    K_eff = k + g sum_k m_k Im v_k''  (a crank spring k),   omega^2 = K_eff / M_eff.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np

#: Out-of-plane inertia of every link [kg m^2] (it never enters the planar dynamics).
IXX = 1e-3


@dataclass(frozen=True)
class Link:
    length: float
    mass: float
    com: float  # [m] along the link from its proximal joint
    inertia: float  # [kg m^2] in-plane, about the centre of mass


@dataclass(frozen=True)
class FourBar:
    crank: Link
    coupler: Link
    rocker: Link
    ground: float  # d [m]
    theta_ref: float  # crank angle [rad] of the assembled configuration q = 0
    branch: int = 1  # +1: B on the left of A -> O4, -1: on the right (the assembly mode)

    def loop(self, theta: float) -> tuple[float, float]:
        """(phi, chi) of the assembly on this linkage's branch (B left or right of A -> O4)."""
        a, b, c = self.crank.length, self.coupler.length, self.rocker.length
        A = a * cmath.exp(1j * theta)
        D = complex(self.ground, 0.0)
        dist = abs(D - A)
        e = (D - A) / dist
        x = (b * b - c * c + dist * dist) / (2 * dist)
        B = A + x * e + self.branch * math.sqrt(b * b - x * x) * 1j * e
        return cmath.phase(B - A), cmath.phase(D - B)

    def reference(self) -> tuple[float, float, float]:
        """Relative joint angles of the URDF's joint origins (the assembled pose at q = 0)."""
        phi, chi = self.loop(self.theta_ref)
        return self.theta_ref, phi - self.theta_ref, chi - phi

    def joints(self, theta: float) -> np.ndarray:
        """The configuration q (3,) of the open chain assembled at crank angle theta."""
        phi, chi = self.loop(theta)
        r1, r2, r3 = self.reference()
        return np.array([theta - r1, phi - theta - r2, chi - phi - r3])

    def energy(self, theta: float, g: float) -> tuple[float, float, float]:
        """(M_eff, V_g', V_g'') along the loop at crank angle theta (module docstring)."""
        a, b, c = self.crank.length, self.coupler.length, self.rocker.length
        phi, chi = self.loop(theta)
        E = [cmath.exp(1j * x) for x in (theta, phi, chi)]
        # b phi' i e^{i phi} + c chi' i e^{i chi} = -a i e^{i theta}
        cols = np.array([[(1j * b * E[1]).real, (1j * c * E[2]).real], [(1j * b * E[1]).imag, (1j * c * E[2]).imag]])
        rhs = -1j * a * E[0]
        d1, d2 = np.linalg.solve(cols, [rhs.real, rhs.imag])
        rhs2 = a * E[0] + b * d1**2 * E[1] + c * d2**2 * E[2]
        dd1, dd2 = np.linalg.solve(cols, [rhs2.real, rhs2.imag])
        s1, s2, s3 = self.crank.com, self.coupler.com, self.rocker.com
        v1, w1 = 1j * s1 * E[0], -s1 * E[0]
        v2 = 1j * a * E[0] + 1j * s2 * d1 * E[1]
        w2 = -a * E[0] + 1j * s2 * dd1 * E[1] - s2 * d1**2 * E[1]
        vB = 1j * a * E[0] + 1j * b * d1 * E[1]
        wB = -a * E[0] + 1j * b * dd1 * E[1] - b * d1**2 * E[1]
        v3 = vB + 1j * s3 * d2 * E[2]
        w3 = wB + 1j * s3 * dd2 * E[2] - s3 * d2**2 * E[2]
        links = (self.crank, self.coupler, self.rocker)
        M = sum(L.mass * abs(v) ** 2 + L.inertia * om**2 for L, v, om in zip(links, (v1, v2, v3), (1.0, d1, d2)))
        V1 = g * sum(L.mass * v.imag for L, v in zip(links, (v1, v2, v3)))
        V2 = g * sum(L.mass * w.imag for L, w in zip(links, (w1, w2, w3)))
        return float(M), float(V1), float(V2)

    def spring_rest(self, theta0: float, k: float, g: float) -> float:
        """Rest angle (joint coordinate) of a crank spring k that makes theta0 an equilibrium."""
        _, V1, _ = self.energy(theta0, g)
        return theta0 - self.theta_ref + V1 / k

    def omega2(self, theta0: float, k: float, g: float) -> float:
        """omega^2 = (k + V_g'') / M_eff at the equilibrium theta0 [rad^2/s^2]."""
        M, _, V2 = self.energy(theta0, g)
        return (k + V2) / M

    def urdf(self) -> str:
        """The open chain with a ``rocker_tip`` frame where the loop closes."""
        parts = ['<?xml version="1.0"?>\n<robot name="four_bar">\n  <link name="ground"/>']
        parent, origin = "ground", "0 0 0"
        for name, link, ref in zip(("crank", "coupler", "rocker"), (self.crank, self.coupler, self.rocker), self.reference()):
            parts.append(
                f'  <link name="{name}"><inertial><origin xyz="{link.com!r} 0 0"/><mass value="{link.mass!r}"/>'
                f'<inertia ixx="{IXX}" iyy="{link.inertia!r}" izz="{link.inertia!r}" ixy="0" ixz="0" iyz="0"/>'
                f"</inertial></link>\n"
                f'  <joint name="{name}_joint" type="revolute"><parent link="{parent}"/><child link="{name}"/>'
                f'<origin xyz="{origin}" rpy="0 {-ref!r} 0"/><axis xyz="0 -1 0"/>'
                f'<limit lower="-6.3" upper="6.3" effort="100" velocity="10"/></joint>'
            )
            parent, origin = name, f"{link.length!r} 0 0"
        parts.append(
            '  <link name="rocker_tip"/>\n  <joint name="rocker_tip_joint" type="fixed"><parent link="rocker"/>'
            f'<child link="rocker_tip"/><origin xyz="{self.rocker.length!r} 0 0"/></joint>\n</robot>'
        )
        return "\n".join(parts)


#: The bundled four-bar (src/pinlin/data/urdf/four_bar.urdf, mjcf/four_bar.xml): a Grashof crank-rocker.
BUNDLED = FourBar(
    crank=Link(0.3, 1.2, 0.12, 0.011),
    coupler=Link(0.8, 2.0, 0.35, 0.1),
    rocker=Link(0.6, 1.5, 0.25, 0.05),
    ground=0.7,
    theta_ref=math.pi / 3,
)

#: A parallelogram (crank = rocker, coupler = ground), assembled hanging down.
PARALLELOGRAM = FourBar(
    crank=Link(0.4, 1.1, 0.15, 0.02),
    coupler=Link(0.8, 2.3, 0.4, 0.12),
    rocker=Link(0.4, 0.9, 0.22, 0.015),
    ground=0.8,
    theta_ref=-math.pi / 2,
    branch=-1,
)
