set title 'GP fitness per generation (tetris)'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'fitness-tetris.png'
plot 'fitness-tetris.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'run-01 best', 'fitness-tetris.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-02 best', 'fitness-tetris.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-03 best', 'fitness-tetris.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'run-04 best', 'fitness-tetris.dat' index 4 using 1:2 with lines lw 2 lc 5 title 'run-05 best'
set terminal svg size 900,600
set output 'fitness-tetris.svg'
plot 'fitness-tetris.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'run-01 best', 'fitness-tetris.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'run-02 best', 'fitness-tetris.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'run-03 best', 'fitness-tetris.dat' index 3 using 1:2 with lines lw 2 lc 4 title 'run-04 best', 'fitness-tetris.dat' index 4 using 1:2 with lines lw 2 lc 5 title 'run-05 best'
