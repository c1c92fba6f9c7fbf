set title 'GP fitness per generation (cartpole)'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'fitness-cartpole.png'
plot 'fitness-cartpole.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-cartpole.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
set terminal svg size 900,600
set output 'fitness-cartpole.svg'
plot 'fitness-cartpole.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-cartpole.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
