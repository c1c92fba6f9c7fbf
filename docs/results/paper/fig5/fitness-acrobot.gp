set title 'GP fitness per generation (acrobot)'
set xlabel 'generation'
set ylabel 'fitness'
set key bottom right
set grid
set terminal pngcairo size 900,600
set output 'fitness-acrobot.png'
plot 'fitness-acrobot.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-acrobot.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
set terminal svg size 900,600
set output 'fitness-acrobot.svg'
plot 'fitness-acrobot.dat' index 0 using 1:2 with lines lw 2 lc 1 title 'best', 'fitness-acrobot.dat' index 1 using 1:2 with lines lw 2 lc 2 title 'population mean'
