#!/bin/sh
cd /work/bed/study/flow/mu2_theta28/tol1e-3_shuffle2/legs/00 && taskset -c 1 /work/bed/lmp_cd -in /work/bed/study/in.chute -log log.lammps -screen none -var reading layer -var L 45 -var seed 2 -var mu 2 -var theta 28 -var tolerance 1e-3 -var duration 7.2 -var max_iterations 100000 -var order shuffle -var stage flow -var start /work/bed/study/start/mu2_theta28/chute.restart
