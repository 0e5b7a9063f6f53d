"""Physical constants (CODATA 2018 exact SI values) and constants derived from them."""

import math

H_PLANCK = 6.62607015e-34  # J s
C_LIGHT = 299792458.0  # m / s
K_BOLTZMANN = 1.380649e-23  # J / K

#: Second radiation constant hc/k, m K.
C2 = H_PLANCK * C_LIGHT / K_BOLTZMANN
#: Prefactor of the paper's series (eq. 3): 2 k^4 / (h^3 c^2), W m^-2 sr^-1 K^-4.
RADIANCE_PREFACTOR = 2.0 * K_BOLTZMANN**4 / (H_PLANCK**3 * C_LIGHT**2)
#: Integral of t^3 / (e^t - 1) over (0, inf).
PI4_OVER_15 = math.pi**4 / 15.0
