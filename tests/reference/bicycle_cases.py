"""The Whipple bicycle benchmark's published numbers, as data.

Source: J. P. Meijaard, J. M. Papadopoulos, A. Ruina and A. L. Schwab, "Linearized dynamics
equations for the balance and steer of a bicycle: a benchmark and review", Proc. R. Soc. A 463
(2007) 1955-1982, doi:10.1098/rspa.2007.1857.  The parameters
are the defaults of :class:`pinlin.model.vehicles.WhippleParameters`.

In roll phi and steer delta (benchmark signs: roll to the right and steer to the right positive),
the linearized equations of the upright bicycle rolling straight at speed v are

    M q'' + v C1 q' + (g K0 + v^2 K2) q = 0,    q = (phi, delta).
"""

import numpy as np

G = 9.81

M = np.array([[80.81722, 2.31941332208709],
              [2.31941332208709, 0.29784188199686]])
C1 = np.array([[0.0, 33.86641391492494],
               [-0.85035641456978, 1.68540397397560]])
K0 = np.array([[-80.95, -2.59951685249872],
               [-2.59951685249872, -0.80329488458618]])
K2 = np.array([[0.0, 76.59734589573222],
               [0.0, 2.65431523794604]])

#: Eigenvalues [1/s] at the speeds [m/s] of the keys, sorted by (real, imaginary) part.
EIGENVALUES = {
    0.0: np.array([-5.53094371765393, -3.13164324790656, 3.13164324790656, 5.53094371765393]),
    5.0: np.array([-14.0783896927982, -0.775341882195845 - 4.46486771378823j,
                   -0.775341882195845 + 4.46486771378823j, -0.322866429004087]),
}

#: Self-stable between these speeds [m/s]: the weave pair's real part crosses zero at the
#: first, the capsize eigenvalue (real) at the second.
WEAVE_SPEED = 4.29238253634111
CAPSIZE_SPEED = 6.02426201538837
