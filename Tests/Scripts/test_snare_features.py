#!/usr/bin/env python3
"""scripts/snare_features.py on synthetic strikes whose features are known, and on bad input.

    python3 Tests/Scripts/test_snare_features.py PATH/TO/snare_features.py

A decaying sine A e^{-a t} sin(2 pi f t) falls by 20 log10(e) a dB a second, so its envelope
falls 20 dB after 20 / (8.686 a) s and 40 dB after twice that; its spectrum is one line at f,
so its centroid and its lowest strong peak are f and its energy lies in f's band. Two such
sines of equal amplitude and decay split the energy in half (to the leakage of the window).
Bad files must give one line on stderr and exit status 2.
"""

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy.io import wavfile

failures = []


def check(condition, what):
    print(('ok   ' if condition else 'FAIL ') + what)
    if not condition:
        failures.append(what)


def run(script, *args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True, timeout=120)


def decaying(rate, seconds, freqs, db_per_s, delay_s=0.0, noise=0.0):
    t = np.arange(int(seconds * rate)) / rate
    a = db_per_s / (20.0 * math.log10(math.e))
    x = np.zeros_like(t)
    on = t >= delay_s
    for f in freqs:
        x[on] += 0.4 * np.exp(-a * (t[on] - delay_s)) * np.sin(2.0 * math.pi * f * (t[on] - delay_s))
    if noise > 0.0:
        x += noise * np.random.default_rng(1).standard_normal(len(t))
    return x.astype(np.float32)


def main():
    script = sys.argv[1]
    rate = 48000
    with tempfile.TemporaryDirectory() as tmp:
        def wav(name, x, r=rate):
            path = os.path.join(tmp, name)
            wavfile.write(path, r, x)
            return path

        # 440 Hz falling 40 dB/s, after 0.2 s of quiet noise (-100 dB): -20 dB at 500 ms, -40 dB at 1000 ms.
        sine = wav('sine.wav', decaying(rate, 1.6, [440.0], 40.0, delay_s=0.2, noise=4e-6))
        # 3 kHz and 7 kHz together, 60 dB/s, stereo 16-bit at 44.1 kHz: half the energy in 2-5 kHz, half in 5-10 kHz.
        pair = decaying(44100, 1.0, [3000.0, 7000.0], 60.0)
        pcm = np.round(np.stack([pair, pair], axis=1) * 32767.0).astype(np.int16)
        pair_path = wav('pair.wav', pcm, 44100)

        result = run(script, '--json', sine, pair_path)
        check(result.returncode == 0, 'two good files exit 0 (stderr: %s)' % result.stderr.strip())
        found = json.loads(result.stdout)
        s, p = found[0], found[1]
        check(abs(s['onset_s'] - 0.199) < 0.002, 'onset after the quiet lead-in: %.4f s (0.199)' % s['onset_s'])
        check(abs(s['tail_centroid_hz'] - 440.0) < 5.0, 'sine: tail centroid %.1f Hz (440)' % s['tail_centroid_hz'])
        check(abs(s['lowest_peak_hz'] - 440.0) < 1.0, 'sine: lowest strong peak %.2f Hz (440)' % s['lowest_peak_hz'])
        check(abs(s['fall_20db_ms'] - 500.0) < 15.0, 'sine: falls 20 dB in %.1f ms (500)' % s['fall_20db_ms'])
        check(abs(s['fall_40db_ms'] - 1000.0) < 15.0, 'sine: falls 40 dB in %.1f ms (1000)' % s['fall_40db_ms'])
        check(s['band_shares']['<1k'] > 0.99, 'sine: share below 1 kHz %.4f (1)' % s['band_shares']['<1k'])
        check(abs(sum(s['band_shares'].values()) - 1.0) < 1e-9, 'band shares sum to 1')
        check(abs(p['tail_centroid_hz'] - 5000.0) < 100.0, 'pair: tail centroid %.0f Hz (5000)' % p['tail_centroid_hz'])
        check(abs(p['lowest_peak_hz'] - 3000.0) < 2.0, 'pair: lowest strong peak %.1f Hz (3000)' % p['lowest_peak_hz'])
        for band in ('2-5k', '5-10k'):
            check(abs(p['band_shares'][band] - 0.5) < 0.02, 'pair: share %s %.3f (0.5)' % (band, p['band_shares'][band]))
        check(abs(p['fall_20db_ms'] - 333.3) < 15.0, 'pair: falls 20 dB in %.1f ms (333)' % p['fall_20db_ms'])
        check(p['fall_40db_ms'] is not None and abs(p['fall_40db_ms'] - 666.7) < 15.0,
              'pair (16 bit, its noise 88 dB down): falls 40 dB in %s ms (667)' % p['fall_40db_ms'])

        table = run(script, sine, pair_path)
        check(table.returncode == 0 and 'sine.wav' in table.stdout and 'pair.wav' in table.stdout
              and 'tail centroid' in table.stdout, 'the table names both files')

        try:
            import soundfile
            flac = os.path.join(tmp, 'sine.flac')
            soundfile.write(flac, decaying(rate, 1.6, [440.0], 40.0, delay_s=0.2, noise=4e-6), rate, subtype='PCM_24')
            result = run(script, '--json', flac)
            check(result.returncode == 0 and abs(json.loads(result.stdout)[0]['lowest_peak_hz'] - 440.0) < 1.0,
                  'FLAC read (soundfile)')
        except ImportError:
            print('skip FLAC (no python3-soundfile)')

        bad = {
            'not audio': os.path.join(tmp, 'text.wav'),
            'missing': os.path.join(tmp, 'missing.wav'),
            'silent': wav('silent.wav', np.zeros(rate, dtype=np.float32)),
            'short': wav('short.wav', decaying(rate, 0.05, [440.0], 40.0)),
            'steady sine': wav('steady.wav', (0.5 * np.sin(2 * math.pi * 440.0 * np.arange(rate) / rate)).astype(np.float32)),
            'noise': wav('noise.wav', (0.1 * np.random.default_rng(2).standard_normal(rate)).astype(np.float32)),
            'swell': wav('swell.wav', (np.sin(math.pi * np.arange(rate) / rate) ** 2
                                       * np.sin(2 * math.pi * 440.0 * np.arange(rate) / rate)).astype(np.float32)),
        }
        with open(bad['not audio'], 'w') as f:
            f.write('not a sound file\n')
        for what, path in bad.items():
            result = run(script, path)
            lines = result.stderr.strip().splitlines()
            check(result.returncode == 2 and len(lines) == 1 and result.stdout == '',
                  '%s: exit %d, %d line(s) on stderr: %s' % (what, result.returncode, len(lines), result.stderr.strip()))
        result = run(script, sine, bad['silent'])
        check(result.returncode == 2 and 'sine.wav' in result.stdout and len(result.stderr.strip().splitlines()) == 1,
              'a bad file among good ones: the good one shown, one line for the bad one, exit 2')

    print('%d failure(s)' % len(failures))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
