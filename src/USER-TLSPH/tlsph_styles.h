/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the one table of styles this package provides, and the two
   ways of registering them (doc/Howto_load.rst):
     - lammpsplugin_init(): for a LAMMPS built with the PLUGIN package
       ("plugin load tlsphplugin.so")
     - tlsph_register_styles(): inserts the creators straight into the style
       maps of a running LAMMPS instance (the lmp_tlsph launcher and the
       Python helper, for LAMMPS builds without PLUGIN such as Debian's),
       and a 'plugin' command into its command map, if it has none, whose
       'plugin load .../tlsphplugin.so' does this again (after 'clear')
   Both print one line: "USER-TLSPH <version> (LAMMPS <version>)".
------------------------------------------------------------------------- */

#ifndef TLSPH_STYLES_H
#define TLSPH_STYLES_H

extern "C" {
// returns 0 on success, 1 if the LAMMPS version differs from the headers
// the package was compiled with (the error is reported through LAMMPS)
int tlsph_register_styles(void *lmp);
// the LAMMPS version of the headers the package was compiled with
const char *tlsph_lammps_version();
// the package's version (the file VERSION)
const char *tlsph_version();
}

#endif
