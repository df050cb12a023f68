#!/bin/sh
cd /work/runs/length/length/L102/tol1e-4_shuffle2/legs/00 && taskset -c 1 /work/runs/bin/lmp_cd_s6 -in /work/runs/length/in.chute -log log.lammps -screen none -var reading count -var seed 2 -var mu 0.5 -var theta 22 -var L 102 -var tolerance 1e-4 -var duration 7.2 -var max_iterations 100000 -var order shuffle -var stage flow -var start /work/runs/length/length/L102/start/chute.restart
