#include "fix_contact_dynamics_contact_stress.h"

#include "domain.h"
#include "update.h"

using namespace LAMMPS_NS;

void ContactStressGauge::after_step(const cd::StepContacts& contacts, double* virial)
{
  contacts_ = &contacts;
  area_dt_ = domain->xprd * domain->yprd * update->dt;
  measured_ = false;
  if (!virial) return;
  const cd::BranchImpulseSums sums = cd::branch_impulse_sums(contacts);
  const double dt = update->dt;
  virial[0] += sums.xx / dt;
  virial[1] += sums.yy / dt;
  virial[3] += sums.xy / dt;
}

void ContactStressGauge::per_atom(const cd::StepContacts& contacts, double** vatom, int atoms)
{
  for (int i = 0; i < atoms; i++)
    for (int k = 0; k < 6; k++) vatom[i][k] = 0.0;
  const double dt = update->dt;
  cd::for_each_branch_impulse_share(contacts, [&](int body, const cd::BranchImpulseSums& share) {
    double* row = vatom[body - 1];
    row[0] += share.xx / dt;
    row[1] += share.yy / dt;
    row[3] += share.xy / dt;
  });
}

double ContactStressGauge::component(int k)
{
  if (!measured_ && contacts_) {
    const cd::BranchImpulseSums sums = cd::branch_impulse_sums(*contacts_);
    double local[4] = {sums.xx, sums.yy, sums.xy, sums.yx};  // m N s
    MPI_Allreduce(local, pressure_, 4, MPI_DOUBLE, MPI_SUM, world);
    for (double& value : pressure_) value = area_dt_ > 0.0 ? value / area_dt_ : 0.0;
    measured_ = true;
  }
  return pressure_[k];
}
