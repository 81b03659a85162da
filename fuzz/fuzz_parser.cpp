/* ----------------------------------------------------------------------
   libFuzzer harness of the USER-TLSPH input parsers (doc/fuzz.md):
     PairTLSPH::settings / PairTLSPHDamage::settings   (pair_style arguments)
     PairTLSPH::coeff, set_material, set_orthotropic     (inline pair_coeff)
     PairTLSPH::read_material_file                       (material files)
   and, when every command was accepted, a short run that uses the values.
   Findings: a crash or sanitizer report (ASan, UBSan, LeakSanitizer), a
   hang, a process exit, and a violated oracle (below, "oracles"): an
   accepted pair_style must give a kernel and cutoff LAMMPS can compute
   with, an accepted material finite derived constants, a finished run a
   finite state and (tlsph/damage) a finite critical stretch > 0.

   Debian's liblammps has no LAMMPS_EXCEPTIONS: its Error::all() and
   Error::one() print and exit(). This file defines both itself; the
   executable's definitions interpose on liblammps's (it is not linked
   -Bsymbolic and calls them through its PLT, checked by the harness's
   self-test at start-up), so every refused input throws Stop, which is
   caught around each command, and the fuzzer goes on with the next input.
   A process exit during an input is therefore a finding: libFuzzer reports
   it ("fuzz target exited").

   One input: byte 0 chooses the set-up, the rest is text, split in lines
     bit 0    dimension 3 (else 2)
     bit 1    pair_style tlsph/damage (else tlsph)
     bits 2-3 number of atom types - 1 (3 means 3 types)
     bit 4    file form: line 2 = the names after 'pair_coeff * * FILE',
              lines 3... = the material file; else lines 2... (up to 8)
              are inline 'pair_coeff' argument lists, one command each
     bit 5    then 'run 3' with fix nve (else 'run 0')
     bit 6    newton off
     bit 7    pair_style issued again after pair_coeff (settings change
              after the materials: PairTLSPH::sync_laws)
   line 1: the pair_style arguments ("h 0.0015" when the line is empty).
   Command lines go through LAMMPS's own input parser (Input::one); the
   characters that parser treats as script syntax ($ variables, # comments,
   quotes) are replaced by '_' first, so that the fuzzer exercises the
   package's parsers, not LAMMPS's variables. The file's bytes are written
   unchanged.
------------------------------------------------------------------------- */

#include "atom.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "lammps.h"
#include "pair_tlsph.h"
#include "pair_tlsph_damage.h"
#include "run.h"
#include "tlsph_styles.h"

#include <mpi.h>
#include <sanitizer/lsan_interface.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <unistd.h>
#include <vector>

namespace {
// thrown by the interposed Error::all / Error::one
struct Stop : std::exception {
  std::string msg;
  explicit Stop(std::string m) : msg(std::move(m)) {}
  const char *what() const noexcept override { return msg.c_str(); }
};
bool g_verbose = false;    // TLSPH_FUZZ_VERBOSE=1: print each command and error
std::string g_matfile;     // the material file of the current input
}    // namespace

/* ---------------------------------------------------------------------- */
// the interposed definitions (signatures of liblammps-dev's error.h)

namespace LAMMPS_NS {
void Error::all(const std::string &file, int line, const std::string &str)
{
  throw Stop("ERROR: " + str + " (" + file + ":" + std::to_string(line) + ")");
}

void Error::one(const std::string &file, int line, const std::string &str)
{
  throw Stop("ERROR on proc 0: " + str + " (" + file + ":" + std::to_string(line) + ")");
}
}    // namespace LAMMPS_NS

using namespace LAMMPS_NS;

namespace {

LAMMPS *new_lammps()
{
  const char *args[] = {"tlsph_fuzz", "-log", "none", "-screen", "none", "-echo", "none", "-nocite"};
  auto lmp = new LAMMPS(sizeof(args) / sizeof(args[0]), const_cast<char **>(args), MPI_COMM_WORLD);
  tlsph_register_styles(lmp);
  return lmp;
}

/* ----------------------------------------------------------------------
   oracles: what an accepted command must leave behind. A violation is a
   finding (abort: libFuzzer saves the input as a crash artifact).
------------------------------------------------------------------------- */

[[noreturn]] void violated(const std::string &what, const std::string &line)
{
  fprintf(stderr, "tlsph_fuzz: ORACLE: %s\n  after the accepted command: %s\n", what.c_str(),
          line.c_str());
  abort();
}

// the protected settings of the pair style (pointers to members, taken in a
// derived class's scope)
struct Peek : PairTLSPH {
  static double h_of(const PairTLSPH *p) { return p->*(&Peek::h); }
  static double cutfactor_of(const PairTLSPH *p) { return p->*(&Peek::cutfactor); }
  static const TLSPH::CubicSpline &kernel_of(const PairTLSPH *p) { return p->*(&Peek::kernel); }
};

bool good(double v) { return std::isfinite(v) && v > 0.0; }

// pair_style: a kernel and a cutoff LAMMPS can compute with (it keeps the
// squared cutoff: its underflow to 0 would mean "no cutoff")
void check_settings(const PairTLSPH *p, const std::string &line)
{
  const double cut = 2.0 * Peek::h_of(p) * Peek::cutfactor_of(p);
  const auto &k = Peek::kernel_of(p);
  if (!good(k.norm) || !good(k.inv_h) || !good(cut) || !good(cut * cut))
    violated(fmt::format("pair_style accepted h = {}, cutfactor = {}: kernel norm {}, 1/h {}, "
                         "cutoff {}, cutoff^2 {}", Peek::h_of(p), Peek::cutfactor_of(p), k.norm,
                         k.inv_h, cut, cut * cut), line);
}

// pair_coeff: every material given has finite, positive derived constants
void check_materials(LAMMPS *lmp, const PairTLSPH *p, const std::string &line)
{
  for (int t = 1; t <= lmp->atom->ntypes; t++) {
    const auto &m = p->material(t);
    if (!(m.rho > 0.0)) continue;    // no material for this type (yet)
    bool ok = good(m.rho) && good(m.c0) && good(m.E_hg);
    if (!m.orthotropic) ok = ok && std::isfinite(m.lambda) && good(m.mu);
    else
      for (double c : m.ortho_law.C) ok = ok && std::isfinite(c);
    if (!ok)
      violated(fmt::format("type {} accepted with rho = {}, c0 = {}, E_hg = {}, lambda = {}, "
                           "mu = {} (orthotropic {})", t, m.rho, m.c0, m.E_hg, m.lambda, m.mu,
                           m.orthotropic), line);
  }
}

// run: a state that is finite everywhere (NaN must be stopped, not run on)
void check_state(LAMMPS *lmp, const std::string &line)
{
  Atom *a = lmp->atom;
  for (int i = 0; i < a->nlocal; i++)
    for (int d = 0; d < 3; d++)
      if (!std::isfinite(a->x[i][d]) || !std::isfinite(a->v[i][d]) || !std::isfinite(a->f[i][d]))
        violated(fmt::format("atom {} has x {} v {} f {} (component {})", a->tag[i], a->x[i][d],
                             a->v[i][d], a->f[i][d], d), line);
  // tlsph/damage: a critical stretch (given, or from Gc) that can break bonds
  if (const auto *p = dynamic_cast<const PairTLSPHDamage *>(lmp->force->pair))
    for (int t = 1; t <= a->ntypes; t++)
      if (p->material(t).rho > 0.0 && !good(p->critical_stretch_of(t)))
        violated(fmt::format("type {} ran with the critical stretch s_c = {}", t,
                             p->critical_stretch_of(t)), line);
}

// one command; false when LAMMPS refused it (the input ends there)
bool command(LAMMPS *lmp, const std::string &line)
{
  if (g_verbose) fprintf(stderr, "> %s\n", line.c_str());
  try {
    if (line.rfind("run ", 0) == 0) {
      // Input::execute_command() deletes the Run it creates only when
      // command() returns: a refused run (init_style, init_one, the first
      // force call) would leak it and send every such input through
      // libFuzzer's second, leak-checking execution. Here it is on the stack.
      std::string steps = line.substr(4);
      char *args[] = {&steps[0]};
      Run run(lmp);
      run.command(1, args);
    } else {
      lmp->input->one(line);
    }
  } catch (Stop &e) {
    if (g_verbose) fprintf(stderr, "  %s\n", e.what());
    return false;
  }
  const auto *p = dynamic_cast<const PairTLSPH *>(lmp->force->pair);
  if (p && line.rfind("pair_style", 0) == 0) check_settings(p, line);
  if (p && p->allocated && line.rfind("pair_", 0) == 0) check_materials(lmp, p, line);
  if (line.rfind("run", 0) == 0) check_state(lmp, line);
  return true;
}

// a fuzzed line as a command line: LAMMPS script syntax neutralised
std::string plain(const std::string &s)
{
  std::string r = s;
  for (char &c : r) {
    if (c == '$' || c == '#' || c == '"' || c == '\'' || c == '&') c = '_';
    else if (c == '\0' || c == '\r' || c == '\n') c = ' ';
  }
  return r;
}

std::vector<std::string> split_lines(const uint8_t *p, size_t n)
{
  std::vector<std::string> lines(1);
  for (size_t k = 0; k < n; k++) {
    if (p[k] == '\n') lines.emplace_back();
    else lines.back() += static_cast<char>(p[k]);
  }
  return lines;
}

void one_input(const uint8_t *data, size_t size)
{
  if (size < 1) return;
  const unsigned cfg = data[0];
  const int dim = (cfg & 1) ? 3 : 2;
  const bool damage = cfg & 2;
  const int ntypes = ((cfg >> 2) & 3) == 3 ? 3 : ((cfg >> 2) & 3) + 1;
  const bool file_form = cfg & 16;
  const bool run_steps = cfg & 32;
  const bool newton_off = cfg & 64;
  const bool reissue = cfg & 128;
  const std::vector<std::string> lines = split_lines(data + 1, size - 1);
  const std::string style = damage ? "tlsph/damage" : "tlsph";
  const std::string ps_args = lines[0].empty() ? std::string("h 0.0015") : plain(lines[0]);

  LAMMPS *lmp = new_lammps();
  std::vector<std::string> deck;
  deck.emplace_back("units si");
  deck.emplace_back("dimension " + std::to_string(dim));
  deck.emplace_back(dim == 2 ? "boundary s s p" : "boundary s s s");
  deck.emplace_back("atom_style peri");
  deck.emplace_back("atom_modify map array");
  if (newton_off) deck.emplace_back("newton off");
  if (dim == 2) {
    deck.emplace_back("lattice sq 0.001");
    deck.emplace_back("region box block 0 4 0 4 -0.5 0.5");
  } else {
    deck.emplace_back("lattice sc 0.001");
    deck.emplace_back("region box block 0 3 0 3 0 3");
  }
  deck.emplace_back("create_box " + std::to_string(ntypes) + " box");
  deck.emplace_back("create_atoms 1 box");
  if (ntypes >= 2) deck.emplace_back("set atom 1*5 type 2");
  if (ntypes >= 3) deck.emplace_back("set atom 6*8 type 3");
  deck.emplace_back(dim == 2 ? "set group all volume 1e-6" : "set group all volume 1e-9");
  deck.emplace_back(dim == 2 ? "set group all mass 7.8e-3" : "set group all mass 7.8e-6");
  // the masses are those of steel, the materials and h are fuzzed: without
  // the overrides of the set-up checks (first, so that the fuzzed arguments
  // may set them again) most runs would stop at the mass/volume or partner
  // check before the force code
  const std::string ps_line =
      "pair_style " + style + " check_partners no check_volume no " + ps_args;
  deck.emplace_back(ps_line);
  if (file_form) {
    std::string text;
    for (size_t k = 2; k < lines.size(); k++) text += lines[k] + "\n";
    FILE *fp = fopen(g_matfile.c_str(), "wb");
    if (!fp) abort();
    fwrite(text.data(), 1, text.size(), fp);
    fclose(fp);
    deck.emplace_back("pair_coeff * * " + g_matfile + " " + (lines.size() > 1 ? plain(lines[1]) : ""));
  } else {
    for (size_t k = 1; k < lines.size() && k <= 8; k++)
      if (lines[k].find_first_not_of(" \t\r") != std::string::npos)
        deck.emplace_back("pair_coeff " + plain(lines[k]));
  }
  if (reissue) deck.emplace_back(ps_line);
  deck.emplace_back("timestep 1e-9");
  if (run_steps) {
    deck.emplace_back("fix 1 all nve");
    deck.emplace_back("run 3");
  } else {
    deck.emplace_back("run 0");
  }
  for (const auto &c : deck)
    if (!command(lmp, c)) break;
  delete lmp;
}

// the interposition works: a refused command throws instead of exiting,
// from the package's code and from liblammps's own (utils::bounds, Input)
void self_test()
{
  LAMMPS *lmp = new_lammps();
  int caught = 0;
  const char *bad[] = {"pair_style tlsph h -1",    // the package: Error::all via _all
                       "no_such_command 1",        // liblammps: Input::execute_command
                       "region box block 0 1"};    // liblammps: Region, utils
  for (const char *c : bad) {
    try {
      lmp->input->one(c);
    } catch (Stop &) {
      caught++;
    }
  }
  delete lmp;
  if (caught != 3) {
    fprintf(stderr, "tlsph_fuzz: self-test: %d of 3 refused commands were caught: the Error "
                    "interposition does not work\n", caught);
    abort();
  }
}

}    // namespace

/* Leaks that LeakSanitizer must not report: allocations of liblammps whose
   owner an exception skips. Input::execute_command() deletes the Command
   object it created (create_atoms, set, ...) after command() returns, not
   when it throws (LAMMPS's own exception builds leak it the same way); the
   harness runs 'run' itself (command() above), the fixed set-up commands
   are not refused, so this is a safety net. A leak only counts as ours if
   no frame of this list is on its stack. */
extern "C" const char *__lsan_default_suppressions()
{
  return "leak:LAMMPS_NS::Input::command_creator\n";
}

extern "C" int LLVMFuzzerInitialize(int *argc, char ***argv)
{
  // Open MPI keeps allocations of its start-up until the process ends: not
  // ours, and libFuzzer's leak check at exit would report them
  // and it would install its own handlers of SIGSEGV, SIGBUS, SIGFPE, SIGILL
  // and SIGABRT: libFuzzer then leaves those signals alone (no crash report,
  // no artifact). None, please: the sanitizers' and libFuzzer's handle them
  setenv("OMPI_MCA_opal_signal", "", 1);
  __lsan_disable();
  MPI_Init(argc, argv);
  __lsan_enable();
  g_verbose = getenv("TLSPH_FUZZ_VERBOSE") != nullptr;
  // the material file of each input (a crash leaves it behind: the script
  // puts it into build-fuzz/tmp)
  const char *tmp = getenv("TLSPH_FUZZ_TMPDIR");
  if (!tmp || !*tmp) tmp = getenv("TMPDIR");
  g_matfile = std::string(tmp && *tmp ? tmp : "/tmp") + "/tlsph_fuzz_" +
      std::to_string(getpid()) + ".tlsph";
  self_test();
  atexit([] { unlink(g_matfile.c_str()); });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  one_input(data, size);
  return 0;
}
