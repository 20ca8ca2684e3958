"""The recorded snare drums the scripts compare renders with: the dev kits of Debian's
hydrogen-drumkits (ForzeeStereo, ColomboAcousticDrumkit)."""

import glob

KITS = '/usr/share/hydrogen/data/drumkits'
RECORDINGS = [
    ('Forzee, snares on', sorted(glob.glob(KITS + '/ForzeeStereo/Snare-[0-4].wav'))),
    ('Forzee, snares off', sorted(glob.glob(KITS + '/ForzeeStereo/SnareOff-[0-4].wav'))),
    ('Colombo, snares on', sorted(glob.glob(KITS + '/ColomboAcousticDrumkit/snare-opaque-*normal[-_]shot*.flac'))),
    ('Colombo, rim shots', sorted(glob.glob(KITS + '/ColomboAcousticDrumkit/snare-opaque-*rimshot*.flac'))),
]
