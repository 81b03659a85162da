#!/usr/bin/env python3
"""The project's basics agree with each other (ctest project.basics):
VERSION holds one version number; CITATION.cff is valid YAML with the fields
of the Citation File Format 1.2.0 that a citation needs and the same version
and licence; CHANGELOG.md has a section for that version; LICENSE is the GNU
GPL version 2 (LAMMPS's licence, whose internal headers the package compiles
against) and the CITATION licence says so; README.md names the licence and
the citation file.

    check_project.py ROOT
"""
import os
import re
import sys

import yaml


def main():
    root = sys.argv[1]
    bad = []

    def read(name):
        p = os.path.join(root, name)
        if not os.path.exists(p):
            bad.append(f'{name} missing')
            return ''
        return open(p, encoding='utf-8').read()

    version = read('VERSION').strip()
    if not re.fullmatch(r'\d+\.\d+\.\d+', version):
        bad.append(f'VERSION is {version!r}, not MAJOR.MINOR.PATCH')
    cff_text = read('CITATION.cff')
    try:
        cff = yaml.safe_load(cff_text) or {}
    except yaml.YAMLError as e:
        cff = {}
        bad.append(f'CITATION.cff is not valid YAML: {e}')
    for key in ('cff-version', 'message', 'title', 'authors', 'version', 'license'):
        if key not in cff:
            bad.append(f'CITATION.cff lacks {key}')
    if str(cff.get('version')) != version:
        bad.append(f"CITATION.cff version {cff.get('version')!r} != VERSION {version!r}")
    if cff.get('license') not in ('GPL-2.0-only', 'GPL-2.0-or-later'):
        bad.append(f"CITATION.cff license {cff.get('license')!r} is not GPL-2.0")
    refs = cff.get('references') or []
    thesis = [r for r in refs if r.get('type') == 'thesis']
    if not thesis or 'smoothed particle hydrodynamics' not in thesis[0].get('title', '').lower():
        bad.append('CITATION.cff does not reference the thesis by its title')
    for r in refs:
        if not r.get('authors') or not r.get('title'):
            bad.append(f"CITATION.cff reference {r.get('title')!r} lacks authors or title")
    changelog = read('CHANGELOG.md')
    if not re.search(r'^## ' + re.escape(version) + r'\b', changelog, re.M):
        bad.append(f'CHANGELOG.md has no "## {version}" section')
    lic = read('LICENSE')
    if 'GNU GENERAL PUBLIC LICENSE' not in lic or 'Version 2, June 1991' not in lic:
        bad.append('LICENSE is not the GNU GPL version 2')
    readme = read('README.md')
    for word in ('LICENSE', 'CITATION.cff'):
        if word not in readme:
            bad.append(f'README.md does not mention {word}')
    for b in bad:
        print('FAILED:', b)
    if not bad:
        print(f'PASSED: version {version}; CITATION.cff, CHANGELOG.md, LICENSE and README agree')
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
