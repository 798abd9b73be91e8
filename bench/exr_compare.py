"""Compares two EXR files bit for bit (compare_images): the same parts (subimages) with the same names
and data windows, the same channel names, types and sampling, and the same stored bits of every sample
(+0 and -0, or two NaNs with different payloads, count as different). Header attributes are not part of
the check: structural ones are covered by the above, timing ones (seconds, dates) are ignored, and any
other that differs is returned as a note."""
from nimbus_tools import EXR_FLOAT, EXR_HALF, EXR_UINT, read_exr

STRUCTURAL_ATTRIBUTES = {"channels", "dataWindow", "chunkCount", "name", "type", "version"}


def is_timing_attribute(name):
    lower = name.lower()
    return "seconds" in lower or "date" in lower or "time" in lower or lower == "utcoffset"


def ulp_distance(bits_a, bits_b, ptype):
    """The largest distance in units in the last place between stored samples of one float or half channel
    (ordered as integers with the sign folded, so -0 and +0 are 0 apart); 0 for uint channels."""
    import numpy as np
    if ptype not in (EXR_FLOAT, EXR_HALF):
        return 0
    sign = np.int64(1) << (31 if ptype == EXR_FLOAT else 15)

    def ordered(bits):
        b = bits.astype(np.int64)
        return np.where(b & sign, -(b & (sign - 1)), b)

    return int(np.abs(ordered(bits_a) - ordered(bits_b)).max()) if bits_a.size else 0


def describe_channel(spec):
    ptype, xs, ys = spec
    text = {EXR_UINT: "uint", EXR_HALF: "half", EXR_FLOAT: "float"}.get(ptype, f"type {ptype}")
    return text if (xs, ys) == (1, 1) else f"{text} sampled {xs}x{ys}"


def compare_images(old_path, new_path):
    """(identical, details, notes) of two EXRs, bit for bit."""
    import numpy as np
    old, new = read_exr(old_path), read_exr(new_path)
    if len(old) != len(new):
        return False, f"{len(old)} parts in OLD, {len(new)} in NEW", []
    problems, notes = [], []
    pixels = channels = total_channels = 0
    max_abs, max_ulps, nonfinite = 0.0, 0, 0
    differing = []
    for index, (a, b) in enumerate(zip(old, new)):
        where = f"part {index} " if len(old) > 1 else ""
        if a.name != b.name:
            problems.append(f"{where}named {a.name!r} in OLD, {b.name!r} in NEW")
        if a.data_window != b.data_window:
            problems.append(f"{where}data window {a.data_window} in OLD, {b.data_window} in NEW")
            continue
        ca, cb = {c[0]: c[1:] for c in a.channels}, {c[0]: c[1:] for c in b.channels}
        only_old, only_new = sorted(set(ca) - set(cb)), sorted(set(cb) - set(ca))
        if only_old or only_new:
            problems.append(f"{where}channels only in OLD: {', '.join(only_old) or '-'}; "
                            f"only in NEW: {', '.join(only_new) or '-'}")
        xmin, ymin, xmax, ymax = a.data_window
        mask = np.zeros((ymax - ymin + 1, xmax - xmin + 1), dtype=bool)
        retyped = []
        for name in sorted(set(ca) & set(cb)):
            total_channels += 1
            if ca[name] != cb[name]:
                retyped.append(f"{name} {describe_channel(ca[name])} -> {describe_channel(cb[name])}")
                continue
            bits_a, bits_b = a.pixels[name], b.pixels[name]
            diff = bits_a != bits_b
            if not diff.any():
                continue
            channels += 1
            differing.append(name if len(old) == 1 else f"{index}:{name}")
            if diff.shape == mask.shape:
                mask |= diff
            else:  # a subsampled channel: its own samples count
                pixels += int(diff.sum())
            va = a.values(name)[diff].astype(np.float64)
            vb = b.values(name)[diff].astype(np.float64)
            d = np.abs(va - vb)
            finite = np.isfinite(d)
            nonfinite += int((~finite).sum())
            if finite.any():
                max_abs = max(max_abs, float(d[finite].max()))
            max_ulps = max(max_ulps, ulp_distance(bits_a[diff], bits_b[diff], ca[name][0]))
        pixels += int(mask.sum())
        if retyped:
            problems.append(f"{where}{len(retyped)} channels change type or sampling ({', '.join(retyped[:4])}"
                            + (", ...)" if len(retyped) > 4 else ")"))
        for key in sorted(set(a.attributes) | set(b.attributes)):
            if key in STRUCTURAL_ATTRIBUTES or is_timing_attribute(key):
                continue
            va = a.attribute_text(key) if key in a.attributes else "(absent)"
            vb = b.attribute_text(key) if key in b.attributes else "(absent)"
            if va != vb:
                notes.append(f"{where}header {key}: {va} in OLD, {vb} in NEW")
    if channels:
        shown = ", ".join(differing[:8]) + (", ..." if len(differing) > 8 else "")
        text = (f"{pixels} pixels differ in {channels} of {total_channels} channels ({shown}), "
                f"max abs difference {max_abs:.6g}, max {max_ulps} ulp")
        if nonfinite:
            text += f", {nonfinite} samples NaN/inf on one side or with other NaN bits"
        problems.insert(0, text)
    return not problems, "; ".join(problems), notes
