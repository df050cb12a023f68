// lmp_cd: Debian's LAMMPS library with this project's styles; accepts every lmp option.
#include <mpi.h>

#include "error.h"
#include "input.h"
#include "lammps.h"
#include "style_registry.h"

// `clear` rebuilds the LAMMPS instance's classes, whose style tables then hold only the styles
// compiled into the library. Input hard-wires the command to Input::clear, which the library
// calls through its procedure linkage table: this definition, in the executable, takes its
// place (ELF symbol interposition). It clears as the command is documented to (the instance
// rebuilt, command-line settings applied again), then registers this project's styles again.
void LAMMPS_NS::Input::clear()
{
  if (narg > 0) error->all(FLERR, "Illegal clear command: it takes no arguments");
  lmp->destroy();
  lmp->create();
  lmp->post_create();
  register_project_styles(lmp);
}

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
