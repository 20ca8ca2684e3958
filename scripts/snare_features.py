#!/usr/bin/env python3
"""Sound features of single drum strikes, for comparing renders with recordings.

    python3 scripts/snare_features.py [--json] [--channel N] FILE [FILE ...]

FILE is a WAV or FLAC file (any sample rate, integer or float samples) holding one strike.
Several files are shown side by side, one column each; --json prints a list of objects, one a
file. Channels are averaged unless --channel N (0-based) picks one (an air-box render's first
channel is the close top microphone).

Definitions (the DC offset removed first, t = 0 at the onset):
  onset       the first sample with |x| >= 0.1 max|x|, less 1 ms (not before the first sample)
  envelope    RMS over a centred 10 ms window, in dB of its largest value
  centroid    spectral centroid (Hz) of the tail 50-300 ms, Hann window, power spectrum
              (the window is cut at the end of the file; fewer than 10 ms of tail: null)
  bands       shares of the energy of the first 300 ms in < 1, 1-2, 2-5, 5-10, > 10 kHz
              (rectangular window with a 5 ms half-Hann taper at its end; they sum to 1)
  fall20/40   time (ms) after which the envelope stays more than 20 / 40 dB below its largest
              value; null when the file ends first
  peak        the lowest strong spectral peak (Hz) of the first 500 ms (Hann, zero-padded):
              the lowest local maximum above 40 Hz that is the largest within +-20 Hz and
              within 12 dB of the spectrum's largest value

Bad input (unreadable, silent, shorter than 100 ms, no strike: no fall of 20 dB after the
envelope's largest value, or that value more than 100 ms after the onset) prints one line on
stderr for that file and the exit status is 2; the other files are still shown.
Needs numpy and scipy; FLAC needs python3-soundfile (WAV is read by scipy without it).
"""

import argparse
import json
import sys

import numpy as np

BANDS = [(0.0, 1000.0), (1000.0, 2000.0), (2000.0, 5000.0), (5000.0, 10000.0), (10000.0, float('inf'))]
BAND_NAMES = ['<1k', '1-2k', '2-5k', '5-10k', '>10k']


class BadInput(Exception):
    pass


def read_audio(path, channel):
    """Samples as float64, mono, and the sample rate."""
    try:
        try:
            import soundfile
            x, rate = soundfile.read(path, dtype='float64', always_2d=True)
        except ImportError:
            if not path.lower().endswith('.wav'):
                raise BadInput('cannot read %s: FLAC needs python3-soundfile' % path)
            from scipy.io import wavfile
            rate, raw = wavfile.read(path)
            x = raw.astype(np.float64)
            if raw.dtype.kind in 'iu':
                info = np.iinfo(raw.dtype)
                x = (x - (info.max + 1 + info.min) / 2.0) / (info.max + 1.0)
            if x.ndim == 1:
                x = x[:, None]
    except BadInput:
        raise
    except Exception as e:  # anything the readers refuse
        raise BadInput('cannot read %s: %s' % (path, str(e).splitlines()[0] if str(e) else type(e).__name__))
    if x.shape[0] == 0:
        raise BadInput('%s: no samples' % path)
    if channel is None:
        mono = x.mean(axis=1)
    elif channel < x.shape[1]:
        mono = x[:, channel]
    else:
        raise BadInput('%s: no channel %d (it has %d)' % (path, channel, x.shape[1]))
    return mono, float(rate)


def envelope_db(x, rate):
    """RMS over a centred 10 ms window, dB of its largest value."""
    n = max(1, int(round(0.010 * rate)))
    power = np.convolve(x * x, np.ones(n) / n, mode='same')
    peak = power.max()
    return 10.0 * np.log10(np.maximum(power, peak * 1e-30) / peak)


def load_strike(path, channel=None):
    """The samples (DC offset removed), the sample rate and the onset's index; BadInput when
    the file is unreadable, not finite, shorter than 100 ms or silent."""
    x, rate = read_audio(path, channel)
    if not np.all(np.isfinite(x)):
        raise BadInput('%s: non-finite samples' % path)
    if len(x) < 0.100 * rate:
        raise BadInput('%s: shorter than 100 ms (%.1f ms)' % (path, 1e3 * len(x) / rate))
    x = x - x.mean()
    top = np.abs(x).max()
    if top < 1e-7:  # below -140 dB of full scale
        raise BadInput('%s: silent' % path)
    onset = max(0, int(np.argmax(np.abs(x) >= 0.1 * top)) - int(round(0.001 * rate)))
    return x, rate, onset


def features(path, channel=None):
    x, rate, onset = load_strike(path, channel)
    env = envelope_db(x, rate)
    peak_at = int(np.argmax(env))
    if peak_at - onset > 0.100 * rate:
        raise BadInput('%s: no strike (the level peaks %.0f ms after the onset)' % (path, 1e3 * (peak_at - onset) / rate))

    def fall(db):
        above = np.nonzero(env[peak_at:] > -db)[0]
        last = peak_at + above[-1] + 1  # the first sample after which it stays below
        return None if last >= len(x) else 1e3 * (last - onset) / rate

    fall20, fall40 = fall(20.0), fall(40.0)
    if fall20 is None:
        raise BadInput('%s: no strike (the level never falls 20 dB)' % path)

    def segment(t0, t1):
        return x[onset + int(round(t0 * rate)):min(len(x), onset + int(round(t1 * rate)))]

    # tail centroid
    tail = segment(0.050, 0.300)
    centroid = None
    if len(tail) >= 0.010 * rate:
        spectrum = np.abs(np.fft.rfft(tail * np.hanning(len(tail)))) ** 2
        f = np.fft.rfftfreq(len(tail), 1.0 / rate)
        if spectrum.sum() > 0.0:
            centroid = float((f * spectrum).sum() / spectrum.sum())

    # band shares of the first 300 ms
    head = segment(0.0, 0.300).copy()
    taper = min(len(head), int(round(0.005 * rate)))
    if taper > 1:
        head[-taper:] *= 0.5 * (1.0 + np.cos(np.pi * np.arange(1, taper + 1) / taper))
    spectrum = np.abs(np.fft.rfft(head)) ** 2
    f = np.fft.rfftfreq(len(head), 1.0 / rate)
    total = spectrum.sum()
    shares = [float(spectrum[(f >= lo) & (f < hi)].sum() / total) for lo, hi in BANDS]

    # lowest strong peak of the first 500 ms
    part = segment(0.0, 0.500)
    nfft = 1 << int(np.ceil(np.log2(4 * len(part))))
    mag = np.abs(np.fft.rfft(part * np.hanning(len(part)), nfft))
    f = np.fft.rfftfreq(nfft, 1.0 / rate)
    db = 20.0 * np.log10(np.maximum(mag, mag.max() * 1e-15))
    usable = f >= 40.0
    strongest = db[usable].max()
    reach = max(1, int(round(20.0 / (rate / nfft))))
    from scipy.ndimage import maximum_filter1d
    local = db == maximum_filter1d(db, size=2 * reach + 1, mode='nearest')
    candidates = np.nonzero(usable & local & (db >= strongest - 12.0))[0]
    candidates = candidates[(candidates > 0) & (candidates < len(db) - 1)]
    peak_hz = None
    if len(candidates):
        i = candidates[0]
        a, b, c = db[i - 1], db[i], db[i + 1]
        den = a - 2.0 * b + c
        peak_hz = float((i + (0.5 * (a - c) / den if den != 0.0 else 0.0)) * rate / nfft)

    return {
        'file': path,
        'sample_rate_hz': rate,
        'onset_s': onset / rate,
        'tail_centroid_hz': centroid,
        'band_shares': dict(zip(BAND_NAMES, shares)),
        'fall_20db_ms': fall20,
        'fall_40db_ms': fall40,
        'lowest_peak_hz': peak_hz,
    }


def table(results):
    def show(v, fmt):
        return 'n/a' if v is None else fmt % v

    rows = [('file', [r['file'].rsplit('/', 1)[-1] for r in results]),
            ('tail centroid 50-300 ms (Hz)', [show(r['tail_centroid_hz'], '%.0f') for r in results])]
    for name in BAND_NAMES:
        rows.append(('share %s Hz, 0-300 ms (%%)' % name, ['%.1f' % (100.0 * r['band_shares'][name]) for r in results]))
    rows += [('fall 20 dB (ms)', [show(r['fall_20db_ms'], '%.0f') for r in results]),
             ('fall 40 dB (ms)', [show(r['fall_40db_ms'], '%.0f') for r in results]),
             ('lowest strong peak (Hz)', [show(r['lowest_peak_hz'], '%.1f') for r in results])]
    label = max(len(name) for name, _ in rows)
    widths = [max(len(row[1][i]) for row in rows) for i in range(len(results))]
    for name, values in rows:
        print(name.ljust(label) + ''.join('  ' + v.rjust(w) for v, w in zip(values, widths)))


def main():
    parser = argparse.ArgumentParser(description='Sound features of single drum strikes (WAV or FLAC).')
    parser.add_argument('files', nargs='+', metavar='FILE')
    parser.add_argument('--json', action='store_true', help='a JSON list, one object a file')
    parser.add_argument('--channel', type=int, default=None, help='use this channel (0-based) instead of their mean')
    args = parser.parse_args()
    if args.channel is not None and args.channel < 0:
        print('snare_features.py: --channel must be >= 0', file=sys.stderr)
        return 2
    results, status = [], 0
    for path in args.files:
        try:
            results.append(features(path, args.channel))
        except BadInput as e:
            print('snare_features.py: %s' % e, file=sys.stderr)
            status = 2
    if args.json:
        print(json.dumps(results, indent=1))
    elif results:
        table(results)
    return status


if __name__ == '__main__':
    sys.exit(main())
