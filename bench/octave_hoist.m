% The three-mass hoist for 10 s with Octave's ode45 (Dormand-Prince), RelTol 1e-8, AbsTol 1e-10.
I1 = 0.80; I2 = 0.45; I3 = 0.25; c1 = 2.4e4; c2 = 9.0e3; Msp = 450; MB = 270;
f = @(t, y) [y(2); (Msp - c1*(y(1)-y(3)))/I1; y(4); (c1*(y(1)-y(3)) - c2*(y(3)-y(5)) - MB)/I2; y(6); c2*(y(3)-y(5))/I3];
opts = odeset('RelTol', 1e-8, 'AbsTol', 1e-10);
tic; [t, y] = ode45(f, linspace(0, 10, 10001), [MB/c1; 0; 0; 0; 0; 0], opts); el = toc;
printf('hoist octave   %.6f s  max M12 %.9g (on the grid)\n', el, max(c1*(y(:,1)-y(:,3))));
