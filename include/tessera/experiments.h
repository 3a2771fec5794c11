// tessera/experiments.h — the two paper experiments as library calls (umbrella header):
//
//  * experiments/seams.h: `run_seams`, Toth 2013 (Table 1 and Figure 5);
//  * experiments/aa.h: `run_aa`, Holländer, Boubekeur & Eisemann 2013 (Table 1, Figures 6a, 7,
//    8);
//  * experiments/common.h: the backend switch (cpu, gl, both) and the one factory interface of
//    the GL backends, which the `tessera_gl` library implements (tessera/gl_experiments.h);
//  * experiments/seams_backend.h, aa_backend.h: each experiment's backend interface and its CPU
//    implementation.
//
// Both calls return plain result structs and print nothing; writing files is the caller's
// business (`tessera seams` / `tessera aa`).
// Tests: tests/unit/experiments_test.cpp, experiments_aa_test.cpp,
// experiments_seams_backend_test.cpp.
#pragma once

#include "tessera/experiments/aa.h"
#include "tessera/experiments/common.h"
#include "tessera/experiments/seams.h"
