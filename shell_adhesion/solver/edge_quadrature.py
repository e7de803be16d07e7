"""Integration along a Q2 edge of the meridian (the cavity's inner surface, its lid's
contact, the pocket): 3-point Gauss on the edge parameter xi in [0, 1], exact for
polynomials of degree 5, and the 1D Q2 shape functions (nodes at xi = 0, 1/2, 1) with
their derivatives d/dxi at those points, (Q, 3) each."""
import math

import numpy as np

GAUSS_X = 0.5 + 0.5 * np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])
GAUSS_W = np.array([5.0, 8.0, 5.0]) / 18.0
N = np.stack([2 * (GAUSS_X - 0.5) * (GAUSS_X - 1), -4 * GAUSS_X * (GAUSS_X - 1),
              2 * GAUSS_X * (GAUSS_X - 0.5)], axis=1)
DN = np.stack([4 * GAUSS_X - 3, 4 - 8 * GAUSS_X, 4 * GAUSS_X - 1], axis=1)
