"""Generate the synthetic records of the IDA example (examples/ida.toml) as PEER .AT2 files.

Run once from the repository root; the records are stored in examples/records/ida/:

    python examples/make_ida_records.py

Ten records of Kanai-Tajimi filtered white noise (:func:`unilateral.loads.synthetic_accelerogram`),
12 s long at 0.01 s, with different seeds and soil frequencies f_g from 1.5 to 4 Hz, each with a
peak ground acceleration of 0.3 g (the study scales them). They are synthetic, not recorded
ground motions: no real record can be shipped with the package. Running the script again writes
the same files (the seeds fix the noise).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from unilateral.loads import STANDARD_GRAVITY, synthetic_accelerogram

FOLDER = Path(__file__).parent / "records" / "ida"
SEEDS = (101, 102, 103, 104, 105, 106, 107, 108, 109, 110)
F_G = np.linspace(1.5, 4.0, len(SEEDS))        # Hz
DURATION, DT, PGA_G = 12.0, 0.01, 0.3


def write_at2(path: Path, record, title: str) -> None:
    """Write ``record`` (m/s^2) as a PEER NGA .AT2 file in units of g, five values per line."""
    a = np.asarray(record.acceleration) / STANDARD_GRAVITY
    lines = ["PEER NGA STRONG MOTION DATABASE RECORD (FORMAT ONLY)",
             f"SYNTHETIC GROUND MOTION, NOT A RECORDED EVENT: {title}",
             "ACCELERATION TIME SERIES IN UNITS OF G",
             f"NPTS= {a.size:7d}, DT= {record.dt:.4f} SEC"]
    for start in range(0, a.size, 5):
        lines.append("".join(f"{x:15.7E}" for x in a[start:start + 5]))
    path.write_text("\n".join(lines) + "\n", encoding="ascii")


def main() -> None:
    FOLDER.mkdir(parents=True, exist_ok=True)
    for k, (seed, f_g) in enumerate(zip(SEEDS, F_G), start=1):
        record = synthetic_accelerogram(DURATION, DT, PGA_G * STANDARD_GRAVITY, seed=seed, f_g=float(f_g),
                                        zeta_g=0.6)
        name = f"ida{k:02d}_seed{seed}.AT2"
        write_at2(FOLDER / name, record, f"KANAI-TAJIMI NOISE, SEED {seed}, F_G {f_g:.3f} HZ, "
                                         f"ZETA_G 0.6, PGA {PGA_G} G (unilateral.loads.synthetic_accelerogram)")
        print(FOLDER / name)


if __name__ == "__main__":
    main()
