#!/bin/sh
cd /work/runs/length/length/L152/tol1e-4_shuffle1/legs/00 && taskset -c 1 /work/runs/bin/lmp_cd_s7d -in /work/runs/length/in.chute -log log.lammps -screen none -var reading count -var seed 1 -var mu 0.5 -var theta 22 -var L 152 -var tolerance 1e-4 -var duration 7.2 -var max_iterations 100000 -var order shuffle -var stage flow -var start /work/runs/length/length/L152/start/chute.restart
