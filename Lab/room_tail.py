#!/usr/bin/env python3
"""A recording room's late reverberation added to rendered strikes, and their whole-strike
distances to the dev kits' recordings with and without it (docs/MODEL.md, "What is missing").

    python3 Lab/room_tail.py --render build/Source/Renderer/snaresim-render STRIKE.wav ...
            [--t60 0.3 0.4] [--under 30 27 25] [--seed 1]

The model, Schroeder's statistical one: past a 4 ms predelay, Gaussian noise decaying
exponentially, below 1 kHz with 1.3 T60 and above it with 0.8 T60 (second-order Butterworth
split; a small room rings longer low), scaled to `under` dB below the energy of the strike's
direct sound. In a diffuse field that ratio is (r / r_c)^2 at a microphone r from the source,
r_c = 0.057 sqrt(V / T60) (Sabine): a 60 m^3 room at T60 0.3 s has r_c = 0.81 m, so at a close
microphone 4 cm from the head the diffuse field lies 26 dB under the direct sound. The tail is
added to the mono strike (its channels averaged). Every distance is the renderer's own
(--distance, the whole-strike distance of docs/MATCHING.md) to the nearest of the 25 snares-on
recordings of the dev kits of Debian's hydrogen-drumkits. Needs numpy, scipy, python3-soundfile.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

KITS = '/usr/share/hydrogen/data/drumkits'
REFS = [f'{KITS}/ForzeeStereo:Snare-*.wav', f'{KITS}/ColomboAcousticDrumkit:snare-opaque*normal*',
        f'{KITS}/BJA_Pacific:SN_*.aiff', f'{KITS}/BJA_Pacific:SN3_*.aiff', f'{KITS}/Millo-Drums_v.1:snare[13].flac']


def room_response(rate, t60, under_db, seed, predelay=0.004, seconds=1.0):
    from scipy.signal import butter, sosfilt
    rng = np.random.default_rng(seed)
    n = int(seconds * rate)
    t = np.arange(n) / rate
    low = sosfilt(butter(2, 1000.0, 'low', fs=rate, output='sos'), rng.standard_normal(n)) * np.exp(-6.91 * t / (1.3 * t60))
    high = sosfilt(butter(2, 1000.0, 'high', fs=rate, output='sos'), rng.standard_normal(n)) * np.exp(-6.91 * t / (0.8 * t60))
    tail = low + high
    tail /= np.sqrt(np.sum(tail ** 2))
    h = np.zeros(n + int(predelay * rate))
    h[0] = 1.0
    h[int(predelay * rate):] += tail * 10.0 ** (-under_db / 20.0)
    return h


def nearest(render, wav):
    args = [render, '--distance', wav, '--json']
    for r in REFS:
        args += ['--ref', r]
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    return json.loads(out)['strikes'][0]['distance_db']


def main():
    import soundfile
    from scipy.signal import fftconvolve
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--render', required=True, help='snaresim-render, for --distance')
    p.add_argument('strikes', nargs='+', help='rendered strikes (WAV)')
    p.add_argument('--t60', type=float, nargs='+', default=[0.3, 0.4])
    p.add_argument('--under', type=float, nargs='+', default=[30.0, 27.0, 25.0], help='dB under the direct sound')
    p.add_argument('--seed', type=int, default=1)
    a = p.parse_args()
    rooms = [(t, u) for t in a.t60 for u in a.under]
    print('strike', 'dry', *(f'T60 {t:g} s, {u:g} dB' for t, u in rooms), sep=' | ')
    sums = np.zeros(1 + len(rooms))
    with tempfile.TemporaryDirectory() as tmp:
        for path in a.strikes:
            x, rate = soundfile.read(path, dtype='float64', always_2d=True)
            x = x.mean(axis=1)
            row = [nearest(a.render, path)]
            for t60, under in rooms:
                y = fftconvolve(x, room_response(rate, t60, under, a.seed))[:len(x)]
                wet = os.path.join(tmp, 'wet.wav')
                soundfile.write(wet, y / np.max(np.abs(y)), rate, subtype='FLOAT')
                row.append(nearest(a.render, wet))
            sums += np.array(row)
            print(os.path.basename(path), *(f'{d:.2f}' for d in row), sep=' | ')
    print('sum', *(f'{d:.1f}' for d in sums), sep=' | ')
    return 0


if __name__ == '__main__':
    sys.exit(main())
