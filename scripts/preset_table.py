#!/usr/bin/env python3
"""Every factory preset's strike beside the recorded snare drums: a Markdown table (numpy, scipy).

    python3 scripts/preset_table.py [--build build] [--work DIR] [--seconds 1.5] [--json] [--presets P,P,...]
                                    [--set KEY=VALUE ...] [--check] [--distance-limit DB] [--check-features]

Each factory preset (the renderer's --help lists them) is struck once at velocities 60, 100 and
127 as the plug-in plays it: snaresim-render --preset NAME --hit 0:VELOCITY, the default model
(the cavity) and --mic mix, 48 kHz, --seconds long. scripts/snare_features.py's features of each
render give one row: tail centroid, band shares of the first 300 ms, -20 / -40 dB times, lowest
strong peak. Below them, the ranges (min-max over the files) of the recorded snare drums of
Debian's hydrogen-drumkits, as scripts/recordings.py lists them: ForzeeStereo Snare-0..4
(snares on), SnareOff-0..4 (snares off), ColomboAcousticDrumkit's plain strokes (snares on).

The goal, per row: the strike's whole-strike distance (docs/MATCHING.md, "The distance of two
strikes") to its nearest snares-on recording of the dev kits (ForzeeStereo Snare-*,
ColomboAcousticDrumkit snare-opaque*normal*, BJA_Pacific SN_* and SN3_*, Millo-Drums_v.1 snare1
and snare3), a snares-off row's to its nearest of ForzeeStereo SnareOff-*, measured by
snaresim-render --distance: at most --distance-limit DB (default 7 dB, the spread between snares
of different kits), else the row is marked "over" and fails.

Sanity checks, per row, reported and marked but failing only with --check-features (the
features are single numbers of two kits' close-miked strokes, which a strike as near the
recordings as another kit's snare can lie outside: the outside air's longer, darker tails):
  - the tail centroid, the 5-10 kHz share and the -40 dB time against the recordings' range
    with a 10 % margin either side (0.9 min .. 1.1 max): a snares-on preset against the
    snares-on recordings (Forzee and Colombo together), a snares-off preset against Forzee's
    snares-off ones; a value outside is marked low or high
  - a snares-on preset's tail centroid over its own with --set snares_engaged=off (the same
    velocity): at least 2.5 or not
A preset plays with its snares off when its render equals the one with snares_engaged=off.

--check: exit status 1 when a row lies farther than the distance limit (with --check-features
also when a checked feature lies outside its window or a ratio under 2.5; the table is printed
either way), and 77 (the test suite's "skipped") when the recordings are missing.
--presets chooses the presets: names or preset files (a file's rows are named after it), for
trying a preset before it becomes a factory one.
--set KEY=VALUE (repeatable) is passed to every render after the preset: the presets with
another setting (--set outside_air=off, --set grid_coarseness=1).
--work DIR keeps the renders there and uses those it finds (delete them after a change of the
model or of --seconds). --json prints every feature (the shares in %), range and check as one
JSON object instead.
Needs snaresim-render built in the build folder (cmake --build build --target snaresim-render)
and the recordings (apt-get install hydrogen-drumkits python3-soundfile). A missing renderer or
recordings: one line on stderr, exit status 2; a render that fails: exit status 1.
"""

import argparse
import datetime
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import recordings  # noqa: E402
import snare_features  # noqa: E402

VELOCITIES = [60, 100, 127]
RATE = 48000
MARGIN = 0.10  # either side of a recorded range
RATIO = 2.5  # snares on / snares off, tail centroid
DISTANCE_LIMIT = 7.0  # dB to the nearest recording: the goal
ON_SETS = ['Forzee, snares on', 'Colombo, snares on']
OFF_SETS = ['Forzee, snares off']

# (key, header, the value from snare_features.features, format)
COLUMNS = [('centroid', 'tail centroid (Hz)', lambda r: r['tail_centroid_hz'], '%.0f'),
           ('5-10k', '5-10 kHz (%)', lambda r: 100.0 * r['band_shares']['5-10k'], '%.2f'),
           ('<1k', '< 1 kHz (%)', lambda r: 100.0 * r['band_shares']['<1k'], '%.1f'),
           ('1-2k', '1-2 kHz (%)', lambda r: 100.0 * r['band_shares']['1-2k'], '%.1f'),
           ('2-5k', '2-5 kHz (%)', lambda r: 100.0 * r['band_shares']['2-5k'], '%.1f'),
           ('>10k', '> 10 kHz (%)', lambda r: 100.0 * r['band_shares']['>10k'], '%.1f'),
           ('fall20', 'fall 20 dB (ms)', lambda r: r['fall_20db_ms'], '%.0f'),
           ('fall40', 'fall 40 dB (ms)', lambda r: r['fall_40db_ms'], '%.0f'),
           ('peak', 'lowest strong peak (Hz)', lambda r: r['lowest_peak_hz'], '%.0f')]
TARGETS = ['centroid', '5-10k', 'fall40']  # checked against the recordings
# The snares-on recordings of the dev kits a strike's distance is measured to (KITDIR:GLOB).
DISTANCE_REFS = [('ForzeeStereo', 'Snare-*.wav'), ('ColomboAcousticDrumkit', 'snare-opaque*normal*'),
                 ('BJA_Pacific', 'SN_*.aiff'), ('BJA_Pacific', 'SN3_*.aiff'),
                 ('Millo-Drums_v.1', 'snare1.flac'), ('Millo-Drums_v.1', 'snare3.flac')]
OFF_DISTANCE_REFS = [('ForzeeStereo', 'SnareOff-*.wav')]  # a snares-off row's: the one snares-off set


class Failed(Exception):
    pass


def values(result):
    return {key: get(result) for key, _, get, _ in COLUMNS}


def presets(render):
    """The factory presets' names, from the renderer's --help."""
    out = subprocess.run([render, '--help'], check=True, capture_output=True, text=True).stdout
    line = next((l for l in out.splitlines() if l.startswith('Presets (--preset')), '')
    return re.findall(r'"([^"]+)"', line)


def render_strike(render, wav, preset, velocity, seconds, snares_off, settings=()):
    """Render one strike to wav unless it is there already."""
    if os.path.exists(wav):
        return
    args = [render, '-o', wav, '--preset', preset, '--hit', '0:%d' % velocity,
            '--seconds', '%g' % seconds, '--sample-rate', str(RATE)]
    for setting in settings:
        args += ['--set', setting]
    if snares_off:
        args += ['--set', 'snares_engaged=off']
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        raise Failed('%s: %s' % (' '.join(args), (done.stderr.strip().splitlines() or ['exit %d' % done.returncode])[-1]))


def distance_refs(refs=DISTANCE_REFS):
    return ['%s:%s' % (os.path.join(recordings.KITS, kit), pattern) for kit, pattern in refs]


def nearest_recordings(render, files, refs):
    """Each file's distance to its nearest recording of refs and that recording's name."""
    if not files:
        return []
    args = [render, '--json']
    for f in files:
        args += ['--distance', f]
    for ref in distance_refs(refs):
        args += ['--ref', ref]
    done = subprocess.run(args, capture_output=True, text=True)
    if done.returncode != 0:
        raise Failed('snaresim-render --distance: %s' % (done.stderr.strip().splitlines() or ['exit %d' % done.returncode])[-1])
    return [(s['distance_db'], os.path.basename(s['nearest'])) for s in json.loads(done.stdout)['strikes']]


def recorded_ranges():
    """Each recorded set's files and (min, max) of every column; None when a set has no files."""
    sets = {}
    for name, files in recordings.RECORDINGS:
        if name not in ON_SETS + OFF_SETS:
            continue
        if not files:
            return None, name
        rows = [values(snare_features.features(f)) for f in files]  # channels averaged
        known = {k: [r[k] for r in rows if r[k] is not None] for k in rows[0]}
        sets[name] = {'files': files,
                      'range': {k: (min(v), max(v)) if v else (None, None) for k, v in known.items()}}
    return sets, None


def window(sets, names):
    """The combined range of the named sets with the margin, for the checked features."""
    return {k: ((1.0 - MARGIN) * min(sets[n]['range'][k][0] for n in names if sets[n]['range'][k][0] is not None),
                (1.0 + MARGIN) * max(sets[n]['range'][k][1] for n in names if sets[n]['range'][k][1] is not None))
            for k in TARGETS}


def check(value, bounds):
    if value is None:
        return None
    return 'low' if value < bounds[0] else 'high' if value > bounds[1] else 'in'


def measure(render, work, seconds, keep, chosen=None, settings=()):
    rows, strikes = [], []
    for preset in chosen or presets(render):
        name = os.path.splitext(os.path.basename(preset))[0] if os.path.isfile(preset) else preset
        # the settings in the file names, so that a --work folder keeps each set apart
        slug = re.sub(r'[^a-z0-9]+', '-', ' '.join([name] + list(settings)).lower()).strip('-')
        for velocity in VELOCITIES:
            on = os.path.join(work, 'preset-%s-v%d.wav' % (slug, velocity))
            off = os.path.join(work, 'preset-%s-v%d-snares-off.wav' % (slug, velocity))
            render_strike(render, on, preset, velocity, seconds, False, settings)
            render_strike(render, off, preset, velocity, seconds, True, settings)
            with open(on, 'rb') as a, open(off, 'rb') as b:
                snares = 'off' if a.read() == b.read() else 'on'
            mine, theirs = values(snare_features.features(on)), values(snare_features.features(off))
            strikes.append(on)
            rows.append({'preset': preset, 'velocity': velocity, 'snares': snares, 'file': on if keep else None,
                         'features': mine, 'snares_off_features': None if snares == 'off' else theirs})
    if not rows:
        raise Failed('%s --help lists no presets' % render)
    for snares, refs in (('on', DISTANCE_REFS), ('off', OFF_DISTANCE_REFS)):
        mine = [(row, strike) for row, strike in zip(rows, strikes) if row['snares'] == snares]
        for (row, _), (distance, nearest) in zip(mine, nearest_recordings(render, [s for _, s in mine], refs)):
            row['distance_db'], row['nearest'] = distance, nearest
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--build', default='build')
    parser.add_argument('--work', default=None, help='keep the renders in this folder and use those found there')
    parser.add_argument('--seconds', type=float, default=1.5, help='length of each render (default 1.5)')
    parser.add_argument('--json', action='store_true', help='one JSON object instead of the Markdown tables')
    parser.add_argument('--check', action='store_true',
                        help='exit 1 if a row is over the distance limit, 77 if the recordings are missing')
    parser.add_argument('--presets', default=None,
                        help='comma-separated preset names or preset files (default: every factory preset)')
    parser.add_argument('--set', action='append', default=[], metavar='KEY=VALUE', dest='settings',
                        help='passed to every render after the preset (repeatable)')
    parser.add_argument('--distance-limit', type=float, default=DISTANCE_LIMIT, metavar='DB',
                        help='a row whose distance to its nearest recording exceeds DB fails (default %g)' % DISTANCE_LIMIT)
    parser.add_argument('--check-features', action='store_true',
                        help='--check also fails a row with a feature outside its window or a ratio under %g' % RATIO)
    args = parser.parse_args()
    if not 0.0 < args.distance_limit < 60.0:
        print('preset_table.py: --distance-limit must be between 0 and 60 dB', file=sys.stderr)
        return 2
    bad = [v for v in args.settings if not re.fullmatch(r'[a-z0-9_]+=[^\s=]+', v)]
    if bad:
        print('preset_table.py: --set wants KEY=VALUE, got %r' % bad[0], file=sys.stderr)
        return 2
    chosen = [p for p in args.presets.split(',') if p] if args.presets else None
    render = os.path.join(args.build, 'Source/Renderer/snaresim-render')
    if not (os.path.isfile(render) and os.access(render, os.X_OK)):
        print('preset_table.py: no renderer at %s (cmake --build %s --target snaresim-render)' % (render, args.build),
              file=sys.stderr)
        return 2
    if not 0.5 <= args.seconds <= 60.0:
        print('preset_table.py: --seconds must be between 0.5 and 60', file=sys.stderr)
        return 2
    try:
        sets, missing = recorded_ranges()
        if sets is None:
            print('preset_table.py: no recordings for %s in %s (apt-get install hydrogen-drumkits)'
                  % (missing, recordings.KITS), file=sys.stderr)
            return 77 if args.check else 2
        if args.work:
            os.makedirs(args.work, exist_ok=True)
            rows = measure(render, args.work, args.seconds, True, chosen, args.settings)
        else:
            with tempfile.TemporaryDirectory() as tmp:
                rows = measure(render, tmp, args.seconds, False, chosen, args.settings)
    except snare_features.BadInput as e:
        print('preset_table.py: %s' % e, file=sys.stderr)
        return 2
    except (Failed, OSError, subprocess.CalledProcessError) as e:
        print('preset_table.py: %s' % e, file=sys.stderr)
        return 1

    windows = {'on': window(sets, ON_SETS), 'off': window(sets, OFF_SETS)}
    for row in rows:
        row['checks'] = {k: check(row['features'][k], windows[row['snares']][k]) for k in TARGETS}
        off = row['snares_off_features']
        ratio = None
        if off and row['features']['centroid'] and off['centroid']:
            ratio = row['features']['centroid'] / off['centroid']
        row['centroid_over_snares_off'] = ratio
        row['centroid_over_snares_off_ok'] = None if ratio is None else ratio >= RATIO
        row['distance_ok'] = row['distance_db'] <= args.distance_limit
        row['features_ok'] = not (any(row['checks'][k] in ('low', 'high') for k in TARGETS)
                                  or row['centroid_over_snares_off_ok'] is False)

    failing = [r for r in rows if not r['distance_ok'] or (args.check_features and not r['features_ok'])]
    outside = [r for r in rows if not r['features_ok']]
    status = 1 if args.check and failing else 0
    if args.json:
        print(json.dumps({'seconds': args.seconds, 'settings': args.settings, 'sample_rate_hz': RATE, 'velocities': VELOCITIES,
                          'margin': MARGIN, 'ratio': RATIO, 'distance_limit_db': args.distance_limit,
                          'features_checked': args.check_features,
                          'rows': rows, 'recordings': sets,
                          'windows': windows, 'distance_references': distance_refs(),
                          'snares_off_distance_references': distance_refs(OFF_DISTANCE_REFS)}, indent=1))
        return status

    def show(v, fmt):
        return 'n/a' if v is None else fmt % v

    # One row per preset and velocity.
    print('| preset | velocity | snares | ' + ' | '.join(h for _, h, _, _ in COLUMNS)
          + ' | centroid / snares off | distance (dB) | nearest recording |')
    print('|---' * (len(COLUMNS) + 6) + '|')
    for row in rows:
        cells = []
        for key, _, _, fmt in COLUMNS:
            cell = show(row['features'][key], fmt)
            if key in TARGETS and row['checks'][key] in ('low', 'high'):
                cell += ' **%s**' % row['checks'][key]
            cells.append(cell)
        ratio = row['centroid_over_snares_off']
        cells.append('-' if row['snares'] == 'off' else 'n/a' if ratio is None
                     else '%.2f' % ratio + ('' if ratio >= RATIO else ' **< %g**' % RATIO))
        cells += ['%.2f' % row['distance_db'] + (' **over %g**' % args.distance_limit if row['distance_ok'] is False else ''),
                  row['nearest']]
        print('| %s | %d | %s | %s |' % (row['preset'], row['velocity'], row['snares'], ' | '.join(cells)))

    # The recordings' ranges, then the windows checked.
    print('\n| recorded (min-max) | files | ' + ' | '.join(h for _, h, _, _ in COLUMNS) + ' |')
    print('|---' * (len(COLUMNS) + 2) + '|')
    for name in ON_SETS + OFF_SETS:
        cells = []
        for key, _, _, fmt in COLUMNS:
            lo, hi = sets[name]['range'][key]
            cells.append('n/a' if lo is None or hi is None else (fmt + '-' + fmt) % (lo, hi))
        print('| %s | %d | %s |' % (name, len(sets[name]['files']), ' | '.join(cells)))
    print()
    for snares, names in (('on', ON_SETS), ('off', OFF_SETS)):
        w = windows[snares]
        print('Snares %s: %s against %s, %d %% either side of their range: tail centroid %.0f-%.0f Hz, '
              '5-10 kHz %.2f-%.2f %%, fall 40 dB %.0f-%.0f ms.'
              % (snares, 'checked' if args.check_features else 'a sanity check (not failing)', ' + '.join(names),
                 round(100 * MARGIN), w['centroid'][0], w['centroid'][1],
                 w['5-10k'][0], w['5-10k'][1], w['fall40'][0], w['fall40'][1]))
    ok = sum(1 for r in rows if r['snares'] == 'on' and r['centroid_over_snares_off_ok'])
    total = sum(1 for r in rows if r['snares'] == 'on')
    print('Tail centroid at least %g times the same preset\'s with snares_engaged=off: %d of %d snares-on rows.'
          % (RATIO, ok, total))
    print('Distance: the whole-strike distance (docs/MATCHING.md) to the nearest of the snares-on recordings %s, '
          'for a snares-off row of %s; %s.'
          % (', '.join('%s %s' % ref for ref in DISTANCE_REFS), ', '.join('%s %s' % ref for ref in OFF_DISTANCE_REFS),
             'checked, at most %g dB' % args.distance_limit))
    print('Features outside their windows or snares lifting the tail less than %g times: %d of %d rows%s.'
          % (RATIO, len(outside), len(rows), '' if not outside else ' (%s)' % ', '.join(
              '%s at %d' % (r['preset'], r['velocity']) for r in outside)))
    print('Rendered %s s at %d Hz, --mic mix, the default model%s; %s.'
          % ('%g' % args.seconds, RATE, ''.join(', --set ' + v for v in args.settings),
             datetime.date.today().isoformat()))
    if args.check:
        print('Check: %s' % ('every row passes' if not failing else '%d rows fail: %s' % (
            len(failing), ', '.join('%s at %d' % (r['preset'], r['velocity']) for r in failing))))
    return status


if __name__ == '__main__':
    sys.exit(main())
