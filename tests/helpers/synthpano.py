"""Synthetic equirectangular panoramas: coloured discs at known (azimuth, elevation), written
out from the contract's pixel <-> ray convention, independent of ``roadsigns.core``."""
import numpy as np


def ray(az_deg, el_deg):
    """The contract's ray d = (cos e cos a, cos e sin a, -sin e)."""
    a, e = np.radians(az_deg), np.radians(el_deg)
    return np.stack(np.broadcast_arrays(np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), -np.sin(e)), -1)


def paint_discs(discs, width):
    """BGR panorama ``width x width/2``, grey, with discs ``(az_deg, el_deg, radius_deg, bgr)``
    on the sphere (pixel centres at +0.5)."""
    height = width // 2
    pano = np.full((height, width, 3), 90, np.uint8)
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    d = ray(np.degrees(2 * np.pi * (u - 0.5))[None, :], np.degrees(np.pi * (0.5 - v))[:, None])
    for az0, el0, radius, colour in discs:
        pano[d @ ray(az0, el0) > np.cos(np.radians(radius))] = colour
    return pano


def disc_pano_box(az, el, radius, width):
    """Analytic panorama box u0, v0, u1, v1 of a disc (azimuth half-width
    asin(sin r / cos e)), columns unwrapped around ``az``."""
    half_az = np.degrees(np.arcsin(np.sin(np.radians(radius)) / np.cos(np.radians(el))))
    height = width // 2
    return np.array([((az - half_az) / 360.0 + 0.5) * width, (0.5 - (el + radius) / 180.0) * height,
                     ((az + half_az) / 360.0 + 0.5) * width, (0.5 - (el - radius) / 180.0) * height])
