#!/usr/bin/python3
"""Independent reference for bmp-eval: ATE and RPE (--fixed_delta) written in numpy from the definitions of
the TUM RGB-D benchmark's evaluate_ate.py and evaluate_rpe.py. Prints "key value" lines.

usage: tum_reference.py GT EST [--max_difference 0.02] [--offset 0] [--scale 1] [--delta 1] [--delta_unit s|f]
"""
import argparse

import numpy as np


def read_poses(path):
    """Dict stamp -> [tx ty tz qx qy qz qw]; a repeated stamp keeps its last line (as the scripts' dict)."""
    with open(path) as f:
        text = f.read()
    poses = {}
    for line in text.replace(",", " ").replace("\t", " ").split("\n"):
        if len(line) == 0 or line[0] == "#":
            continue
        fields = [float(v) for v in line.split(" ") if v.strip() != ""]
        if len(fields) > 1:
            poses[fields[0]] = fields[1:8]
    return poses


def associate(first, second, offset, max_difference):
    # All pairs closer than max_difference (numpy only to keep the all-pairs scan fast; same float ops).
    second_array = np.array(second, dtype=np.float64)
    candidates = []
    for a in first:
        diff = np.abs(a - (second_array + offset))
        candidates += [(float(diff[k]), a, second[k]) for k in np.nonzero(diff < max_difference)[0]]
    candidates.sort()
    used_a, used_b, matches = set(), set(), []
    for _, a, b in candidates:
        if a in used_a or b in used_b:
            continue
        used_a.add(a)
        used_b.add(b)
        matches.append((a, b))
    matches.sort()
    return matches


def horn(model, data):
    """model, data: 3xN arrays. Returns rot, trans, per-column error."""
    model_c = model - model.mean(axis=1, keepdims=True)
    data_c = data - data.mean(axis=1, keepdims=True)
    W = np.zeros((3, 3))
    for col in range(model.shape[1]):
        W += np.outer(model_c[:, col], data_c[:, col])
    U, _, Vh = np.linalg.svd(W.T)
    S = np.identity(3)
    if np.linalg.det(U) * np.linalg.det(Vh) < 0:
        S[2, 2] = -1
    rot = U @ S @ Vh
    trans = data.mean(axis=1) - rot @ model.mean(axis=1)
    error = np.sqrt(np.sum((rot @ model + trans[:, None] - data) ** 2, axis=0))
    return rot, trans, error


def pose_matrix(p):
    q = np.array(p[3:7], dtype=np.float64)
    q *= np.sqrt(2.0 / np.dot(q, q))
    q = np.outer(q, q)
    return np.array([
        [1.0 - q[1, 1] - q[2, 2], q[0, 1] - q[2, 3], q[0, 2] + q[1, 3], p[0]],
        [q[0, 1] + q[2, 3], 1.0 - q[0, 0] - q[2, 2], q[1, 2] - q[0, 3], p[1]],
        [q[0, 2] - q[1, 3], q[1, 2] + q[0, 3], 1.0 - q[0, 0] - q[1, 1], p[2]],
        [0.0, 0.0, 0.0, 1.0]])


def find_closest_index(L, t):
    beginning, difference, best, end = 0, abs(L[0] - t), 0, len(L)
    while beginning < end:
        middle = (end + beginning) // 2
        if abs(L[middle] - t) < difference:
            difference = abs(L[middle] - t)
            best = middle
        if t == L[middle]:
            return middle
        elif L[middle] > t:
            end = middle
        else:
            beginning = middle + 1
    return best


def ominus(a, b):
    return np.linalg.inv(a) @ b


def rpe(gt, est, delta, unit, offset, scale):
    stamps_gt = sorted(gt)
    stamps_est = sorted(est)
    index_est = stamps_est if unit == "s" else list(range(len(stamps_est)))
    n = len(stamps_est)
    pairs = []
    for i in range(n):
        j = find_closest_index(index_est, index_est[i] + delta)
        if j != n - 1:
            pairs.append((i, j))
    max_dt = 2 * np.median([s - t for s, t in zip(stamps_gt[1:], stamps_gt[:-1])])
    trans, rot = [], []
    for i, j in pairs:
        e0, e1 = stamps_est[i], stamps_est[j]
        g0 = stamps_gt[find_closest_index(stamps_gt, e0 + offset)]
        g1 = stamps_gt[find_closest_index(stamps_gt, e1 + offset)]
        if abs(g0 - (e0 + offset)) > max_dt or abs(g1 - (e1 + offset)) > max_dt:
            continue
        est_rel = ominus(pose_matrix(est[e1]), pose_matrix(est[e0]))
        est_rel[0:3, 3] *= scale
        error = ominus(est_rel, ominus(pose_matrix(gt[g1]), pose_matrix(gt[g0])))
        trans.append(np.linalg.norm(error[0:3, 3]))
        rot.append(np.arccos(min(1, max(-1, (np.trace(error[0:3, 0:3]) - 1) / 2))))
    return np.array(trans), np.array(rot)


def print_stats(prefix, values, factor=1.0):
    print("%s.count %d" % (prefix, len(values)))
    print("%s.rmse %.12f" % (prefix, np.sqrt(np.dot(values, values) / len(values)) * factor))
    print("%s.mean %.12f" % (prefix, np.mean(values) * factor))
    print("%s.median %.12f" % (prefix, np.median(values) * factor))
    print("%s.std %.12f" % (prefix, np.std(values) * factor))
    print("%s.min %.12f" % (prefix, np.min(values) * factor))
    print("%s.max %.12f" % (prefix, np.max(values) * factor))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("gt")
    parser.add_argument("est")
    parser.add_argument("--max_difference", type=float, default=0.02)
    parser.add_argument("--offset", type=float, default=0.0)
    parser.add_argument("--scale", type=float, default=1.0)
    parser.add_argument("--delta", type=float, default=1.0)
    parser.add_argument("--delta_unit", default="s")
    args = parser.parse_args()
    gt = read_poses(args.gt)
    est = read_poses(args.est)
    matches = associate(list(gt), list(est), args.offset, args.max_difference)
    data = np.array([gt[a][0:3] for a, b in matches]).T
    model = np.array([est[b][0:3] for a, b in matches]).T * args.scale
    _, _, ate = horn(model, data)
    print_stats("ate", ate)
    trans, rot = rpe(gt, est, args.delta, args.delta_unit, args.offset, args.scale)
    print_stats("rpe_trans", trans)
    print_stats("rpe_rot_deg", rot, 180.0 / np.pi)


if __name__ == "__main__":
    main()
