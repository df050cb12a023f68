#!/bin/sh
cd /work/bed/study/flow/mu0.05_theta20/tol1e-4_shuffle2/legs/00 && taskset -c 1 /work/bed/lmp_cd -in /work/bed/study/in.chute -log log.lammps -screen none -var reading layer -var L 45 -var seed 2 -var mu 0.05 -var theta 20 -var tolerance 1e-4 -var duration 7.2 -var max_iterations 100000 -var order shuffle -var stage flow -var start /work/bed/study/start/mu0.05_theta20/chute.restart
