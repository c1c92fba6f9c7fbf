set title '3-segment swimmer: best fitness per generation'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'population-sizes.png'
plot 'population-sizes.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'population 25 best', 'population-sizes.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population 50 best', 'population-sizes.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'population 100 best'
set terminal svg size 900,600
set output 'population-sizes.svg'
plot 'population-sizes.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'population 25 best', 'population-sizes.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population 50 best', 'population-sizes.dat' index 2 using 1:2 with lines lw 2 lc 3 title 'population 100 best'
