#pragma once
// Mode extraction on the free DOFs: which modes (a count, or all below a frequency), how
// (backend, shift, factorisation), and what happened (status, work, times). Input errors in
// the request throw InputError; a failed or partial solve is returned as a status so that the
// stage can record it and exit with code 3.
#include <optional>
#include <string>

#include "modal/eigen_backends.hpp"
#include "modal/eigen_operator.hpp"

namespace hm::modal {

/// Either `count` lowest modes, or every mode with f ≤ `max_frequency_hz`; not both.
struct ModeRequest {
  int count = 0;
  std::optional<double> max_frequency_hz;  ///< [Hz]
  std::string context = "modes";           ///< names the request (scene key) in messages
};

enum class EigenBackend { arpack, spectra, dense };
std::string to_string(EigenBackend b);

struct EigenOptions {
  EigenBackend backend = EigenBackend::arpack;
  /// σ [rad²/s²]. Default: −1e-8 · tr(K)/tr(M), just below the spectrum (K − σM is then
  /// positive definite even for a free-free structure, whose rigid-body modes have λ = 0).
  std::optional<double> shift;
  Factorisation factorisation = Factorisation::automatic;
  LanczosOptions lanczos;
  int first_block = 12;  ///< first nev of a max_frequency_hz request; doubled until past f_max
};

struct EigenSolution {
  EigenPairs pairs;  ///< λ ascending, the modes that answer the request
  EigenBackend backend = EigenBackend::arpack;
  double shift = 0.0;
  Factorisation factorisation = Factorisation::simplicial_ldlt;
  double factorisation_seconds = 0.0;
  int solves = 0;  ///< Lanczos runs (> 1 when a frequency request had to grow nev)
};

/// Solves K φ = λ M φ on the free DOFs (K, M already reduced). The Lanczos backends fall back to
/// the dense solver when the problem is too small for a Lanczos basis (nev + 1 ≥ n).
/// Throws InputError for a malformed request or more modes than free DOFs.
EigenSolution solve_eigenproblem(const SparseMatrix& stiffness, const SparseMatrix& mass,
                                 const ModeRequest& request, const EigenOptions& options = {});

/// The default shift −1e-8 · tr(K)/tr(M) [rad²/s²].
double default_shift(const SparseMatrix& stiffness, const SparseMatrix& mass);

}  // namespace hm::modal
