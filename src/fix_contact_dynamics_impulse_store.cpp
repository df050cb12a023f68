#include "fix_contact_dynamics_impulse_store.h"

#include <cstring>

#include "cd/impulse_row.h"
#include "memory.h"

using namespace LAMMPS_NS;

ImpulseStore::ImpulseStore(Memory* memory, int max_contacts)
    : memory_(memory), max_contacts_(max_contacts), width_(cd::impulse_row::width(max_contacts))
{
}

ImpulseStore::~ImpulseStore()
{
  memory_->destroy(rows_);
}

void ImpulseStore::grow(int nmax)
{
  memory_->grow(rows_, nmax, width_, "contact/dynamics:history");
}

void ImpulseStore::copy(int from, int to)
{
  std::memcpy(rows_[to], rows_[from], sizeof(double) * cd::impulse_row::used(rows_[from]));
}

void ImpulseStore::clear(int i)
{
  cd::impulse_row::clear(rows_[i]);
}

int ImpulseStore::pack(int i, double* buf) const
{
  const int n = cd::impulse_row::used(rows_[i]);
  std::memcpy(buf, rows_[i], sizeof(double) * n);
  return n;
}

int ImpulseStore::unpack(int i, const double* buf)
{
  const int n = cd::impulse_row::used(buf);
  std::memcpy(rows_[i], buf, sizeof(double) * n);
  return n;
}

int ImpulseStore::pack_restart(int i, double* buf) const
{
  const int n = pack(i, buf + 1);
  buf[0] = n + 1;
  return n + 1;
}

int ImpulseStore::size_restart(int i) const
{
  return 1 + cd::impulse_row::used(rows_[i]);
}

int ImpulseStore::entries_in(const double* values)
{
  return cd::impulse_row::entries(values);
}

void ImpulseStore::unpack_restart(int i, const double* values)
{
  std::memcpy(rows_[i], values, sizeof(double) * cd::impulse_row::width(entries_in(values)));
}

cd::Local2 ImpulseStore::carried(const cd::PairKey& key) const
{
  return cd::impulse_row::find(rows_[key.row], key.partner);
}

bool ImpulseStore::append(const cd::PairKey& key, cd::Local2 impulse)
{
  return cd::impulse_row::append(rows_[key.row], max_contacts_, key.partner, impulse);
}

double ImpulseStore::memory_usage(int nmax) const
{
  return static_cast<double>(nmax) * width_ * sizeof(double);
}
