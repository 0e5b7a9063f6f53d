"""Kernels for the optics: natural vignetting (cos^4 law, paper eq. 13)."""

import math

from numba import njit, prange


@njit(cache=True)
def cos4_pixel(dy, dx, focal_length):
    """cos^4 of the angle between the optical axis and the ray to an offset (dy, dx), metres.

    cos(beta) = f / sqrt(f^2 + r^2), so cos^4 = (f^2 / (f^2 + r^2))^2 with no trigonometry.
    """
    f2 = focal_length * focal_length
    c2 = f2 / (f2 + dy * dy + dx * dx)
    return c2 * c2


@njit(cache=True, parallel=True)
def cos4_map(rows, cols, centre_row, centre_col, pitch, focal_length, out):
    """cos^4 factor of every pixel centre of a rows x cols array.

    The optical axis meets the array at (centre_row, centre_col) in pixel-index units, which
    is a half-integer for even sizes, so both odd and even arrays are symmetric.
    """
    for i in prange(rows):
        dy = (i - centre_row) * pitch
        for j in range(cols):
            out[i, j] = cos4_pixel(dy, (j - centre_col) * pitch, focal_length)
    return out


def cone_factor_f_number(f_number):
    """sin^2 of the image-side cone half-angle for a lens obeying the sine condition."""
    return 1.0 / (4.0 * f_number * f_number)


def cone_factor_paper_fov(fov):
    """The paper's eq. 12 as written: the field of view used as the cone angle."""
    return math.sin(0.5 * fov) ** 2
