// lmp_cd: Debian's LAMMPS library with this project's styles; accepts every lmp option.
#include <mpi.h>

#include "input.h"
#include "lammps.h"
#include "style_registry.h"

int main(int argc, char** argv)
{
  MPI_Init(&argc, &argv);
  {
    LAMMPS_NS::LAMMPS lmp(argc, argv, MPI_COMM_WORLD);
    LAMMPS_NS::register_project_styles(&lmp);
    lmp.input->file();
  }
  MPI_Finalize();
  return 0;
}
