// Validation of the deck's pass-through solver lists ("Linear Solver"->"Belos", "Ifpack2",
// "MueLu", "Amesos2") before a run (and under --check), by the packages' own validators:
// every entry is checked alone against the package's list of valid parameters (Belos GMRES
// getValidParameters, Ifpack2 AdditiveSchwarz's and Ifpack2::getValidParameters for the
// subdomain list, MueLu's MasterList, Amesos2 KLU2's), so that the message names it;
// then the package is set up on a tiny matrix with the deck's settings (Belos
// setParameters, the Schwarz preconditioner, the KLU2 factorization, MueLu's smoother
// factory) and explicit ranges where a package would crash instead of refusing
// (MueLu "max levels" = 0 is a SIGSEGV in Trilinos 13.2). A bad entry is an InputError
// naming "Linear Solver-><package>-><parameter>" and what is expected.
#pragma once
#include <Teuchos_ParameterList.hpp>
#include <string>

#include "deck/Config.hpp"

namespace stentor {

// Throws InputError for the first bad entry. Cheap (milliseconds): the packages the deck
// does not use are not touched.
void validate_linear_solver(const LinearSolverConfig& cfg);

// The lists LinearSolver gives Belos GMRES and the Ifpack2 Schwarz preconditioner: the
// deck's values, then its pass-through list on top.
Teuchos::RCP<Teuchos::ParameterList> belos_parameters(const LinearSolverConfig& cfg);
Teuchos::ParameterList schwarz_parameters(const LinearSolverConfig& cfg);

// Teuchos' validation message on one line, without the file/line header and the list of
// every valid parameter (a "Did you mean ...?" hint is kept).
std::string teuchos_short_message(const std::string& what);

// " (did you mean 'X'?)" for the name of `valid` nearest to `name` (deck/Schema.hpp's edit
// distance, ignoring case like the deck's own suggestions), or "".
std::string did_you_mean(const std::string& name, const Teuchos::ParameterList& valid);

// MueLu's part (MueLuPreconditioner.cpp, where MueLu's headers are): the user list's
// names and types against MueLu's MasterList, "smoother: type"/"coarse: type" by MueLu's
// smoother factory, ranges that MueLu does not check. `xml` as in LinearSolverConfig.
void validate_muelu_parameters(const std::string& xml);

}  // namespace stentor
