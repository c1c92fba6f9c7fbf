set title 'GP fitness per generation (cartpole-quick)'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'fitness-cartpole-quick.png'
plot 'fitness-cartpole-quick.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'run-01 best', 'fitness-cartpole-quick.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-02 best', 'fitness-cartpole-quick.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-03 best', 'fitness-cartpole-quick.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'run-04 best', 'fitness-cartpole-quick.dat' index 4 using 1:2 with lines lw 2 lc 5 title 'run-05 best', 'fitness-cartpole-quick.dat' index 5 using 1:2 with lines lw 2 lc 6 title 'run-06 best', 'fitness-cartpole-quick.dat' index 6 using 1:2 with lines lw 2 lc 7 title 'run-07 best', 'fitness-cartpole-quick.dat' index 7 using 1:2 with lines lw 2 lc 8 title 'run-08 best'
set terminal svg size 900,600
set output 'fitness-cartpole-quick.svg'
plot 'fitness-cartpole-quick.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'run-01 best', 'fitness-cartpole-quick.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-02 best', 'fitness-cartpole-quick.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-03 best', 'fitness-cartpole-quick.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'run-04 best', 'fitness-cartpole-quick.dat' index 4 using 1:2 with lines lw 2 lc 5 title 'run-05 best', 'fitness-cartpole-quick.dat' index 5 using 1:2 with lines lw 2 lc 6 title 'run-06 best', 'fitness-cartpole-quick.dat' index 6 using 1:2 with lines lw 2 lc 7 title 'run-07 best', 'fitness-cartpole-quick.dat' index 7 using 1:2 with lines lw 2 lc 8 title 'run-08 best'
