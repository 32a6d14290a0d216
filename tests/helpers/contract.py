"""The contract's pose formulas written out longhand, independent of ``roadsigns.core``,
to check the plugin's results against."""
import numpy as np


def Rz(a_deg):
    a = np.radians(a_deg)
    return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])


def Ry(a_deg):
    a = np.radians(a_deg)
    return np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])


def Rx(a_deg):
    a = np.radians(a_deg)
    return np.array([[1, 0, 0], [0, np.cos(a), -np.sin(a)], [0, np.sin(a), np.cos(a)]])


NED_TO_ENU = np.array([[0, 1, 0], [1, 0, 0], [0, 0, -1.0]])


def expected_stations(drive, times, lever_arm_m, boresight_rpy_deg):
    """Panorama centres and R_world_from_pano from an analytic drive (grid heading)."""
    e, n, u, roll, pitch, grid = drive.state(times)
    b_roll, b_pitch, b_yaw = boresight_rpy_deg
    R_bp = Rz(b_yaw) @ Ry(b_pitch) @ Rx(b_roll)
    centres, rotations = [], []
    for k in range(len(times)):
        R_wb = NED_TO_ENU @ Rz(grid[k]) @ Ry(pitch[k]) @ Rx(roll[k])
        centres.append(np.array([e[k], n[k], u[k]]) + R_wb @ np.asarray(lever_arm_m, float))
        rotations.append(R_wb @ R_bp)
    return np.array(centres), np.array(rotations)


def angle_between_deg(Ra, Rb):
    """Angle of the rotation taking Ra to Rb, degrees (batched)."""
    cos = (np.trace(np.swapaxes(Ra, -1, -2) @ Rb, axis1=-2, axis2=-1) - 1) / 2
    return np.degrees(np.arccos(np.clip(cos, -1, 1)))


def quat_to_matrix(q_wxyz):
    w, x, y, z = q_wxyz
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
