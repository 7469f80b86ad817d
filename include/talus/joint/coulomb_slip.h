#pragma once

#include <talus/base/exact_sum.h>
#include <talus/joint/joint_properties.h>

#include <vector>

namespace talus
{

/// Sub-contact state flags.
enum SubContactState : unsigned char
{
  intact = 0,   ///< never failed: cohesion and tensile strength hold
  slipping = 1, ///< at the shear limit this step
  open = 2,     ///< separated (no normal force) this step
  failed = 4    ///< has failed once: residual strength (eqs. 36-37)
};

/// The arrays of one batch of sub-contacts that a joint model reads and
/// writes: structure of arrays so the loop vectorises and the model is
/// chosen once per batch, not per sub-contact.
struct SubContactBatch
{
  /// Sub-contacts in the batch: indices 0 to size - 1 of the arrays, or
  /// with `indices` those size that it lists.
  unsigned int size = 0;
  const unsigned int* indices = nullptr;
  const double* area = nullptr;          ///< A_c, m^2
  const double* du_normal = nullptr;     ///< eq. 21, m (positive = opening)
  const double* du_shear = nullptr;      ///< eq. 22, 3 per sub-contact, m
  double* normal_displacement = nullptr; ///< U^n: < 0 = closure, m
  double* normal_force = nullptr;        ///< F^n, N (compression positive)
  double* shear_force = nullptr;         ///< F^s, 3 per sub-contact, N
  double* shear_displacement = nullptr;  ///< total shear displacement U^s, 3 per sub-contact, m
                                         ///< (dilation limit and direction)
  double* dilation = nullptr;            ///< opening from dilation so far (eq. 42), m
  unsigned char* state = nullptr;
  /// Continuously yielding sub-contacts only: yield_state_size doubles
  /// each (continuously_yielding.h); null when no material yields so.
  double* yield = nullptr;
  /// Joint material of each sub-contact (an index into the list given to
  /// the model); null: all take the first.
  const unsigned char* material = nullptr;
  /// Per sub-contact: whether its frictional work is this rank's to count
  /// (a model split among ranks without a SubContactExchange computes a
  /// contact on every rank that holds both blocks; one of them counts it);
  /// null: all are.
  const unsigned char* counted = nullptr;
  /// Per sub-contact: whether this rank computes it; one with 0 is left as
  /// it is (another rank computes it and sends its state:
  /// SubContactExchange). Null: all are.
  const unsigned char* computed = nullptr;
};

/// Coulomb slip with tension cut-off, cohesion, dilation and loss of
/// strength at failure (eqs. 24-43), applied to every sub-contact of the
/// batch. Returns the frictional work done this step (J), for the energy
/// balance: an exact sum, the same however the sub-contacts are split.
ExactSum coulomb_slip(const JointProperties& joint, SubContactBatch& batch);
/// The same with a joint material per sub-contact (batch.material), each
/// an index into `joints`; sub-contacts of materials of other models are
/// left alone.
ExactSum coulomb_slip(const std::vector<JointProperties>& joints, SubContactBatch& batch);

} // namespace talus
