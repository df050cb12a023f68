#!/bin/sh
cd /work/bed/study/floor/tol1e-5_shuffle1/legs/00 && taskset -c 1 /work/bed/lmp_cd -in /work/bed/study/in.chute -log log.lammps -screen none -var reading layer -var L 45 -var seed 1 -var mu 0.5 -var theta 12 -var duration 0.9 -var max_iterations 100000 -var tolerance 1e-5 -var order shuffle -var stage flow -var start /work/bed/study/floor/tol1e-4_shuffle1/chute.restart
