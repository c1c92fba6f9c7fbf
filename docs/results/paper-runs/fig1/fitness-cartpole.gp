set title 'GP fitness per generation (cartpole)'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'fitness-cartpole.png'
plot 'fitness-cartpole.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'run-01 best', 'fitness-cartpole.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-02 best', 'fitness-cartpole.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-03 best', 'fitness-cartpole.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'run-04 best', 'fitness-cartpole.dat' index 4 using 1:2 with lines lw 2 lc 5 title 'run-05 best'
set terminal svg size 900,600
set output 'fitness-cartpole.svg'
plot 'fitness-cartpole.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'run-01 best', 'fitness-cartpole.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-02 best', 'fitness-cartpole.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-03 best', 'fitness-cartpole.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'run-04 best', 'fitness-cartpole.dat' index 4 using 1:2 with lines lw 2 lc 5 title 'run-05 best'
