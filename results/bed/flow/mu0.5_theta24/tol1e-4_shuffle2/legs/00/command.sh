#!/bin/sh
cd /work/bed/study/flow/mu0.5_theta24/tol1e-4_shuffle2/legs/00 && taskset -c 0 /work/bed/lmp_cd -in /work/bed/study/in.chute -log log.lammps -screen none -var reading layer -var L 45 -var seed 2 -var mu 0.5 -var theta 24 -var tolerance 1e-4 -var duration 7.2 -var max_iterations 100000 -var order shuffle -var stage flow -var start /work/bed/study/start/mu0.5_theta24/chute.restart
